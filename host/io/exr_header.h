#pragma once
// One string attribute of an EXR file's header, read without its pixels: what a run checks of the
// files an earlier run left in its output folder (job/render_job.cpp: their reference frame, in
// files that hold motion layers).
#include <initializer_list>
#include <optional>
#include <string>

namespace dicsynth {

// The string attribute `name` of `path`'s header, where the header also lists at least one of
// `channels`; none where it does not, where the file cannot be read as an EXR, or where the header
// has no string attribute of that name. The header is read once, without the pixels.
std::optional<std::string> exrStringAttributeWithChannel(const std::string& path, const std::string& name,
                                                         std::initializer_list<const char*> channels);

}  // namespace dicsynth
