#pragma once
// Pictures of ground-truth layers (`dicsynth preview`, `render --preview`): each layer of an EXR as
// a PNG a person can look at and put in a report: the values in a perceptually uniform colour map
// (viridis; turbo for labels such as objectId; gray for radiance and masks), NaN in neutral gray,
// a colour bar with the range, the layer's name and unit written on the picture. Vectors (disp,
// flow, distortion, fieldError) are shown as their length and, for disp and flow, per component.
// Images wider than `maxWidth` are shown every k-th pixel (k an integer), so each shown value is
// one of the file's. A file that is not dicsynth's shows each float channel as itself.
// Done by OpenImageIO in libdicsynth_oiio.so (files/oiio_module/preview.cpp).
#include <string>
#include <vector>

namespace dicsynth {

struct PreviewFiles {
  std::vector<std::string> written;  // the PNGs, <outputDir>/<stem>.<layer>.png
  std::vector<std::string> skipped;  // "channel or layer: why"
};

// `outputDir` must exist. Throws InputError("PATH: reason") for an unreadable file.
PreviewFiles previewExr(const std::string& exrPath, const std::string& outputDir, const std::string& stem,
                        int maxWidth = 800);

}  // namespace dicsynth
