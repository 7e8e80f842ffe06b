#pragma once
// One string attribute of an EXR file's header, read without its pixels: what a run checks of the
// files an earlier run left in its output folder (job/render_job.cpp: their reference frame).
#include <initializer_list>
#include <optional>
#include <string>

namespace dicsynth {

// The attribute `name` of `path`'s header, or none where the file cannot be read as an EXR or the
// header has no string attribute of that name.
std::optional<std::string> exrStringAttribute(const std::string& path, const std::string& name);

// Whether `path`'s header lists any of `channels` (false where it cannot be read as an EXR).
bool exrHasAnyChannel(const std::string& path, std::initializer_list<const char*> channels);

}  // namespace dicsynth
