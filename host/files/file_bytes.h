#pragma once
// A file's whole content read once, with the stamp (core/file_stamp.h) it had while it was read:
// decoders then work on these bytes, so what is decoded, hashed and recorded is one content,
// however long the decoding takes. Reading by path instead, a texture renamed over (an editor's
// save, `dicsynth speckle -o`, another job writing it again) while it was decoded made the stamp
// before and after differ, and three such renames in a row refused the texture as being written
// (the sweep audit of 2026-11-28).
#include <optional>
#include <string>

#include "core/file_stamp.h"

namespace dicsynth {

struct FileBytes {
  std::string bytes;
  FileStamp stamp;  // of the file opened, the same before and after the reading
};

// The content of the regular file `path` names (symbolic links followed), or nullopt when it was
// written in place while it was read (its size or times moved, or it grew past the size it had; the
// status-change time alone also moves when a rename over the path takes the file's name, which is
// no change).
// A file renamed over `path` during the reading is not a change: the bytes are those of the file
// opened, and the stamp is that file's. Throws InputError("PATH: reason") when it does not exist, is a
// folder or not a regular file (a device or pipe: /dev/zero never ends), cannot be read, or is
// larger than the memory available (files/image_limits.h).
std::optional<FileBytes> readFileBytes(const std::string& path);

}  // namespace dicsynth
