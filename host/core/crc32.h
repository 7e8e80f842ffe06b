#pragma once
// CRC-32 (ISO-HDLC: zlib's crc32, Python's zlib.crc32) by libdeflate (PCLMUL: ~4x zlib 1.2.13's, the
// same value), of a byte string or of a whole file: what sweep records, texture contents and the
// scene file's text are compared by.
#include <cstdint>
#include <string>
#include <string_view>

#include "core/file_stamp.h"

namespace dicsynth {

std::uint32_t crc32Of(std::string_view bytes);
// The CRC-32 of the file `path` names, read to its end. Throws Error naming the file when it
// cannot be opened or read.
std::uint32_t fileCrc32(const std::string& path);

// A file read as one content: the stamp it was read under and its bytes' CRC-32 (a texture's, a
// Field.load mesh's), what a sweep point records as an asset it rendered with.
struct FileContent {
  std::string path;
  FileStamp stamp;
  std::uint32_t crc32 = 0;
};

// Whether `path` still holds the content read under `stamp` with CRC-32 `crc32`: the stamp
// unchanged, or the same size and CRC (a touch, a copy of the same bytes over it, another job
// writing the same file again move the stamp, not the content). False when it cannot be read.
bool fileStillHolds(const std::string& path, const FileStamp& stamp, std::uint32_t crc32);

}  // namespace dicsynth
