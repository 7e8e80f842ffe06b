#pragma once
// CRC-32 (ISO-HDLC: zlib's crc32, Python's zlib.crc32) by libdeflate (PCLMUL: ~4x zlib 1.2.13's, the
// same value), of a byte string or of a whole file: what sweep records, texture contents and the
// scene file's text are compared by.
#include <cstdint>
#include <string>
#include <string_view>

namespace dicsynth {

std::uint32_t crc32Of(std::string_view bytes);
// The CRC-32 of the file `path` names, read to its end. Throws Error naming the file when it
// cannot be opened or read.
std::uint32_t fileCrc32(const std::string& path);

}  // namespace dicsynth
