// point.json layout: one JSON member per line, in a fixed order, written and read by this file only
// (the product links no JSON parser). A record in any other shape counts as missing, so the point is
// rendered again: a damaged record can cost time, never a wrong "complete".
#include "sweep/point_record.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/json.h"

namespace dicsynth::sweep {
namespace fs = std::filesystem;
namespace {

std::uint32_t fileCrc32(const fs::path& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw Error("cannot read '" + path.string() + "'");
  uLong crc = crc32(0L, Z_NULL, 0);
  static thread_local std::vector<unsigned char> buffer(1 << 20);
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), f)) > 0) crc = crc32(crc, buffer.data(), uInt(n));
  const bool failed = std::ferror(f) != 0;
  std::fclose(f);
  if (failed) throw Error("cannot read '" + path.string() + "': read error");
  return std::uint32_t(crc);
}

// Records list files sorted by name.
bool byName(const PointFile& a, const PointFile& b) { return a.name < b.name; }

std::string hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", v);
  return buf;
}

// Reads a JSON string starting at s[pos] == '"'; returns the end position after the closing quote.
std::optional<std::string> unquote(const std::string& s, std::size_t& pos) {
  if (pos >= s.size() || s[pos] != '"') return std::nullopt;
  std::string out;
  for (++pos; pos < s.size(); ++pos) {
    const char c = s[pos];
    if (c == '"') {
      ++pos;
      return out;
    }
    if (c != '\\') {
      out += c;
      continue;
    }
    if (++pos >= s.size()) return std::nullopt;
    switch (s[pos]) {
      case '"': out += '"'; break;
      case '\\': out += '\\'; break;
      case 'n': out += '\n'; break;
      case 'r': out += '\r'; break;
      case 't': out += '\t'; break;
      case 'u': {  // json::quote writes \u00XX for control characters only
        if (pos + 4 >= s.size()) return std::nullopt;
        out += char(std::stoi(s.substr(pos + 1, 4), nullptr, 16));
        pos += 4;
        break;
      }
      default: return std::nullopt;
    }
  }
  return std::nullopt;
}

// `  "name": VALUE,` → VALUE text (without the trailing comma), or nullopt.
std::optional<std::string> member(const std::string& line, const std::string& name) {
  const std::string prefix = "  " + json::quote(name) + ": ";
  if (line.rfind(prefix, 0) != 0) return std::nullopt;
  std::string value = line.substr(prefix.size());
  if (!value.empty() && value.back() == ',') value.pop_back();
  return value;
}

std::optional<std::string> stringValue(const std::string& text) {
  std::size_t pos = 0;
  auto s = unquote(text, pos);
  if (!s || pos != text.size()) return std::nullopt;
  return s;
}

template <class T>
std::optional<T> numberValue(const std::string& text) {
  std::istringstream in(text);
  in.imbue(std::locale::classic());
  T v{};
  if (!(in >> v) || !in.eof()) return std::nullopt;
  return v;
}

}  // namespace

std::uint32_t crc32Of(std::string_view bytes) {
  uLong crc = crc32(0L, Z_NULL, 0);
  // zlib takes uInt lengths: feed at most 1 GiB at a time.
  for (std::size_t at = 0; at < bytes.size(); at += std::size_t(1) << 30) {
    const std::size_t n = std::min(bytes.size() - at, std::size_t(1) << 30);
    crc = crc32(crc, reinterpret_cast<const Bytef*>(bytes.data() + at), uInt(n));
  }
  return std::uint32_t(crc);
}

PointFile AssetChecksums::of(const std::string& path) {
  const fs::path absolute = fs::absolute(path).lexically_normal();
  std::error_code ec;
  const std::uintmax_t bytes = fs::file_size(absolute, ec);
  const fs::file_time_type modified = ec ? fs::file_time_type{} : fs::last_write_time(absolute, ec);
  if (ec) throw Error("cannot read '" + absolute.string() + "': " + ec.message());
  {
    std::lock_guard lock(mutex_);
    if (auto it = entries_.find(absolute.string());
        it != entries_.end() && it->second.bytes == bytes && it->second.modified == modified)
      return {absolute.string(), bytes, it->second.crc32};
  }
  const std::uint32_t crc = fileCrc32(absolute);
  std::lock_guard lock(mutex_);
  entries_[absolute.string()] = {bytes, modified, crc};
  return {absolute.string(), bytes, crc};
}

std::vector<PointFile> AssetChecksums::of(const std::vector<std::string>& paths) {
  std::vector<PointFile> files;
  for (const std::string& path : paths) files.push_back(of(path));
  std::sort(files.begin(), files.end(), byName);
  files.erase(std::unique(files.begin(), files.end(), [](const PointFile& a, const PointFile& b) { return a.name == b.name; }),
              files.end());
  return files;
}

std::vector<PointFile> scanPointFiles(const std::string& folder) {
  std::vector<PointFile> files;
  for (const fs::directory_entry& e : fs::directory_iterator(folder)) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || name == kPointRecordName || name.empty() || name[0] == '.') continue;
    files.push_back({name, e.file_size(), fileCrc32(e.path())});
  }
  std::sort(files.begin(), files.end(), byName);
  return files;
}

void writePointRecord(const std::string& folder, const PointRecord& r) {
  std::string t = "{\n";
  t += "  \"dicsynth_point\": 2,\n";
  t += "  \"index\": " + std::to_string(r.index) + ",\n";
  t += "  \"key\": " + json::quote(r.key) + ",\n";
  t += "  \"parameters\": " + r.parametersJson + ",\n";
  t += "  \"seed\": " + std::to_string(r.seed) + ",\n";
  t += "  \"spp\": " + std::to_string(r.samplesPerPixel) + ",\n";
  t += "  \"backend\": " + json::quote(r.backend) + ",\n";
  t += "  \"precision\": " + json::quote(r.precision) + ",\n";
  t += "  \"device\": " + json::quote(r.device) + ",\n";
  t += "  \"render_seconds\": " + json::number(r.renderSeconds) + ",\n";
  t += "  \"host\": " + json::quote(r.host) + ",\n";
  t += "  \"finished_utc\": " + json::quote(r.finishedUtc) + ",\n";
  auto list = [&t](const std::vector<PointFile>& files) {
    for (std::size_t i = 0; i < files.size(); ++i)
      t += "    {\"name\": " + json::quote(files[i].name) + ", \"bytes\": " + std::to_string(files[i].bytes) +
           ", \"crc32\": \"" + hex32(files[i].crc32) + "\"}" + (i + 1 < files.size() ? ",\n" : "\n");
  };
  t += "  \"files\": [\n";
  list(r.files);
  t += "  ],\n  \"assets\": [\n";
  list(r.assets);
  t += "  ]\n}\n";
  writeTextAtomically((fs::path(folder) / kPointRecordName).string(), t);
}

std::optional<PointRecord> readPointRecord(const std::string& folder) {
  std::ifstream in(fs::path(folder) / kPointRecordName);
  if (!in) return std::nullopt;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  // Fixed layout: "{", 13 members, the file lines, "  ],", "  \"assets\": [", the asset lines, "  ]",
  // "}". A record of layout 1 (without assets) counts as missing: it cannot tell whether its textures
  // changed, so its point is rendered again.
  if (lines.size() < 19 || lines[0] != "{" || lines[lines.size() - 1] != "}" || lines[lines.size() - 2] != "  ]")
    return std::nullopt;
  PointRecord r;
  auto str = [&](std::size_t i, const char* name) -> std::optional<std::string> {
    auto v = member(lines[i], name);
    return v ? stringValue(*v) : std::nullopt;
  };
  auto version = member(lines[1], "dicsynth_point");
  auto index = member(lines[2], "index");
  auto key = str(3, "key");
  auto params = member(lines[4], "parameters");
  auto seed = member(lines[5], "seed");
  auto spp = member(lines[6], "spp");
  auto backend = str(7, "backend"), precision = str(8, "precision"), device = str(9, "device");
  auto seconds = member(lines[10], "render_seconds");
  auto host = str(11, "host"), finished = str(12, "finished_utc");
  if (!version || *version != "2" || !index || !key || !params || !seed || !spp || !backend || !precision ||
      !device || !seconds || !host || !finished || lines[13] != "  \"files\": [")
    return std::nullopt;
  auto i = numberValue<std::int64_t>(*index);
  auto s = numberValue<std::uint32_t>(*seed);
  auto n = numberValue<int>(*spp);
  auto sec = *seconds == "null" ? std::optional<double>(0) : numberValue<double>(*seconds);
  if (!i || !s || !n || !sec) return std::nullopt;
  r.index = *i;
  r.key = *key;
  r.parametersJson = *params;
  r.seed = *s;
  r.samplesPerPixel = *n;
  r.backend = *backend;
  r.precision = *precision;
  r.device = *device;
  r.renderSeconds = *sec;
  r.host = *host;
  r.finishedUtc = *finished;
  // `    {"name": ..., "bytes": N, "crc32": "xxxxxxxx"}[,]` lines from lines[k] up to the line `end`.
  auto readList = [&lines](std::size_t& k, const std::string& end, std::vector<PointFile>& out) {
    for (; k < lines.size() && lines[k] != end; ++k) {
      std::string line = lines[k];
      if (!line.empty() && line.back() == ',') line.pop_back();
      const std::string head = "    {\"name\": ";
      if (line.rfind(head, 0) != 0 || line.back() != '}') return false;
      std::size_t pos = head.size();
      auto name = unquote(line, pos);
      if (!name) return false;
      unsigned long long bytes = 0;
      char crc[9] = {0};
      int used = 0;
      const std::string rest = line.substr(pos);
      if (std::sscanf(rest.c_str(), ", \"bytes\": %llu, \"crc32\": \"%8[0-9a-f]\"}%n", &bytes, crc, &used) != 2 ||
          std::size_t(used) != rest.size() || std::string(crc).size() != 8)
        return false;
      out.push_back({*name, bytes, std::uint32_t(std::stoul(crc, nullptr, 16))});
    }
    return k < lines.size();
  };
  std::size_t k = 14;
  if (!readList(k, "  ],", r.files) || ++k >= lines.size() || lines[k] != "  \"assets\": [") return std::nullopt;
  ++k;
  if (!readList(k, "  ]", r.assets) || k + 2 != lines.size()) return std::nullopt;
  if (r.files.empty()) return std::nullopt;  // a point always writes files
  return r;
}

bool pointFilesIntact(const std::string& folder, const PointRecord& record, const std::string& key,
                      bool verifyChecksums, AssetChecksums& assets) {
  if (record.key != key) return false;
  for (const PointFile& a : record.assets) {
    try {
      const PointFile now = assets.of(a.name);
      if (now.bytes != a.bytes || now.crc32 != a.crc32) return false;
    } catch (const Error&) {
      return false;  // gone or unreadable: the point cannot be as it was
    }
  }
  for (const PointFile& f : record.files) {
    const fs::path path = fs::path(folder) / f.name;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) != f.bytes || ec) return false;
    if (verifyChecksums) {
      try {
        if (fileCrc32(path) != f.crc32) return false;
      } catch (const Error&) {
        return false;
      }
    }
  }
  return true;
}

}  // namespace dicsynth::sweep
