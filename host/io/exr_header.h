#pragma once
// One string attribute of an EXR file's header, read without its pixels: what a run checks of the
// files an earlier run left in its output folder (job/render_job.cpp: their reference frame).
#include <optional>
#include <string>

namespace dicsynth {

// The attribute `name` of `path`'s header, or none where the file cannot be read as an EXR or the
// header has no string attribute of that name.
std::optional<std::string> exrStringAttribute(const std::string& path, const std::string& name);

}  // namespace dicsynth
