#include "cli/error_line.h"

#include "core/source_place.h"

namespace dicsynth::cli {

std::string errorLine(const std::string& message) { return withKind("error", message); }

}  // namespace dicsynth::cli
