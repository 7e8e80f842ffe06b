#include "sweep/sweep_runner.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/crc32.h"
#include "core/error.h"
#include "core/exact_number.h"
#include "core/module_folder.h"
#include "core/progress.h"
#include "core/warning.h"
#include "core/worker_pool.h"
#include "job/output_writers.h"
#include "job/render_job.h"
#include "model/layers.h"
#include "scene/define_value.h"
#include "shared/rng.h"
#include "sweep/manifest.h"
#include "sweep/point_record.h"
#include "sweep/run_lock.h"

namespace dicsynth {
namespace {
namespace fs = std::filesystem;

struct Shard {
  std::int64_t index = 0, count = 1;
  std::string origin;  // for messages: "--shard 1/4" or "SLURM_ARRAY_TASK_ID=2 ..."
};

std::optional<std::int64_t> parseInteger(const char* text) {
  if (text == nullptr || *text == '\0') return std::nullopt;
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(text, &end, 10);
  if (errno != 0 || *end != '\0') return std::nullopt;
  return v;
}

// --shard I/N, else the Slurm job array's task (0-based from SLURM_ARRAY_TASK_MIN), else 0/1.
Shard resolveShard(const std::string& option) {
  Shard s;
  if (!option.empty()) {
    const auto slash = option.find('/');
    const auto i = slash == std::string::npos ? std::nullopt : parseInteger(option.substr(0, slash).c_str());
    const auto n = slash == std::string::npos ? std::nullopt : parseInteger(option.substr(slash + 1).c_str());
    // strtoll skips leading blanks: " 0/2" is refused as --frames " 2" is (digits only).
    const bool digitsOnly = option.find_first_not_of("0123456789/") == std::string::npos;
    if (!digitsOnly || !i || !n || *n < 1 || *i < 0 || *i >= *n)
      throw InputError("--shard " + option + ": expected I/N with 0 <= I < N");
    return {*i, *n, "--shard " + option};
  }
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (id == nullptr || count == nullptr) return s;
  const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
  const char* max = std::getenv("SLURM_ARRAY_TASK_MAX");
  const char* step = std::getenv("SLURM_ARRAY_TASK_STEP");
  const auto i = parseInteger(id), n = parseInteger(count), m = min ? parseInteger(min) : std::optional<std::int64_t>(0);
  std::string origin = std::string("SLURM_ARRAY_TASK_ID=") + id + " SLURM_ARRAY_TASK_COUNT=" + count +
                       " SLURM_ARRAY_TASK_MIN=" + (min ? min : "(unset)");
  if (max) origin += std::string(" SLURM_ARRAY_TASK_MAX=") + max;
  if (step) origin += std::string(" SLURM_ARRAY_TASK_STEP=") + step;
  // Arrays may start at 1 (--array=1-8): the shard is the task's offset from the array's first. An
  // array with a step (--array=0-6:2) or gaps (--array=0,2,5) is refused where Slurm says so: its
  // tasks' offsets are not 0..N-1, and shards went unrendered in silence (the cluster trial of
  // 2026-11-29: tasks 0 and 2 rendered shards 0/4 and 2/4, tasks 4 and 6 failed, 1 and 3 never ran).
  const auto st = step ? parseInteger(step) : std::optional<std::int64_t>(1);
  const auto mx = max ? parseInteger(max) : std::nullopt;
  const bool contiguous = st && *st == 1 && (!max || (mx && m && n && *mx - *m + 1 == *n));
  if (!i || !n || !m || *n < 1 || *i - *m < 0 || *i - *m >= *n || !contiguous)
    throw InputError(origin + ": cannot shard by these (expected a contiguous array, step 1, such as --array=0-7; or give --shard I/N)");
  return {*i - *m, *n, origin};
}

std::string hostName() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof buf - 1) != 0) return "";
  return buf;
}

std::string utcNow() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string readWholeFile(const std::string& path) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) throw InputError(path + ": cannot read the scene file");
  std::string text;
  char buf[1 << 16];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) text.append(buf, n);
  std::fclose(f);
  return text;
}

// A point's values for messages: "noise=0, blur=1.5".
std::string pointValues(const SweepPoint& point) {
  std::string values;
  for (const auto& [name, value] : point.values) values += (values.empty() ? "" : ", ") + name + "=" + value.defineText();
  return values;
}

// A point's key as named fields, in order; "name=value" joined by spaces is the key its record
// holds (runSweep builds them: everything that determines the point's files).
using KeyFields = std::vector<std::pair<std::string, std::string>>;

std::string joinKey(const KeyFields& fields) {
  std::string key;
  for (const auto& [name, value] : fields) key += (key.empty() ? "" : " ") + name + "=" + value;
  return key;
}

// What differs between a point's recorded key and this run's fields, for people: "spp 16 (now 4),
// downscale 8 (now 1)"; the scene by its content. In the recorded key each field's value runs to
// the next field's name, searched in order (a define's value may itself hold "=" and spaces).
std::string keyDifference(const std::string& recorded, const KeyFields& now) {
  std::vector<std::string> values;
  std::size_t at = 0;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const std::string name = (k ? " " : "") + now[k].first + "=";
    const std::size_t start = recorded.find(name, at);
    if (start == std::string::npos) return "a record of another dicsynth version";
    if (k) values.back() = recorded.substr(at, start - at);
    at = start + name.size();
    values.emplace_back();
  }
  values.back() = recorded.substr(at);
  std::string out;
  for (std::size_t k = 0; k < now.size(); ++k) {
    const std::string& was = values[k];
    const std::string& is = now[k].second;
    if (was == is) continue;
    if (!out.empty()) out += ", ";
    out += now[k].first == "scene_crc32" ? "the scene file's content (changed since)"
                                         : now[k].first + " " + (was.empty() ? "(none)" : was) + " (now " +
                                               (is.empty() ? "(none)" : is) + ")";
  }
  return out;
}

// Progress (core/progress.h): the points done of this shard, and the images (cameras × frames)
// rendered per second; the points/s and the ETA count the points rendered, not those skipped.
class Progress {
 public:
  Progress(std::int64_t total, bool terminal) : bar_("sweep", "points", total, terminal) {}
  void update(std::int64_t done, std::int64_t skipped, std::int64_t images) {
    const double elapsed = bar_.elapsedSeconds();
    char rate[48];
    std::snprintf(rate, sizeof rate, "%.2f img/s", elapsed > 0 ? double(images) / elapsed : 0.0);
    bar_.update(done, rate, skipped);
  }

 private:
  ProgressBar bar_;
};

// A manifest whose points were rendered with several precisions or devices says so: shards on other
// machines (or drivers) each resolve --precision auto on their own device, and fp32 differs between
// devices in the last bits.
// "fp32 on A: 2 points; fp64 on B: 1 point": a manifest's points counted by what tells them apart.
std::string pointCounts(const std::map<std::string, std::int64_t>& counts,
                        const std::function<std::string(const std::string&)>& name) {
  std::string list;
  for (const auto& [what, count] : counts)
    list += (list.empty() ? "" : "; ") + name(what) + ": " + std::to_string(count) + " point" + (count == 1 ? "" : "s");
  return list;
}

void warnMixedDevices(const sweep::ManifestSummary& summary) {
  if (summary.renderedWith.size() < 2) return;
  const std::string list = pointCounts(summary.renderedWith, [](const std::string& what) { return what; });
  warn("the manifest's points were rendered with " + std::to_string(summary.renderedWith.size()) +
       " precisions or devices (" + list + "): --precision auto chooses per device; give --precision (and the same "
       "device or driver to every shard) to render them alike");
}

// Likewise for the builds of dicsynth that rendered the points: a sweep resumed with a rebuilt or
// updated binary (manifest.json's "run" names the build that wrote the manifest; each point's
// "build" its own).
void warnMixedBuilds(const sweep::ManifestSummary& summary) {
  if (summary.builds.size() < 2) return;
  const std::string list = pointCounts(summary.builds, [](const std::string& build) {
    return build.empty() ? std::string("not recorded") : build.substr(0, 12);
  });
  warn("the manifest's points were rendered by " + std::to_string(summary.builds.size()) +
       " builds of dicsynth (" + list + "; each point's \"build\" in manifest.json): values may differ between "
       "builds; render the sweep with one binary to have them alike");
}

// The merge's line for the points not complete: "; missing or damaged: point_00003, point_00004".
std::string missingText(const sweep::ManifestSummary& summary) {
  if (summary.complete == summary.total) return "";
  std::string t = "; missing or damaged: ";
  for (std::size_t k = 0; k < summary.missing.size(); ++k) t += (k ? ", " : "") + pointFolderName(summary.missing[k]);
  const std::int64_t more = summary.total - summary.complete - std::int64_t(summary.missing.size());
  if (more > 0) t += " and " + std::to_string(more) + " more";
  return t;
}

// A parameter may not take the name of one of manifest.csv's own columns: the file would have two
// columns of one name (csv.DictReader then read a parameter `index` as the point's index: the
// cluster trial of 2026-11-29). The sweep's alone: `compare --sweep seed=1,2` writes no manifest.
void checkManifestColumns(const SweepPlan& plan) {
  std::vector<std::string> columns(std::begin(sweep::kManifestLeadColumns), std::end(sweep::kManifestLeadColumns));
  columns.insert(columns.end(), std::begin(sweep::kManifestTrailColumns), std::end(sweep::kManifestTrailColumns));
  for (const std::string& name : plan.names)
    if (std::find(columns.begin(), columns.end(), name) != columns.end()) {
      std::string list;
      for (const std::string& c : columns) list += (list.empty() ? "" : ", ") + c;
      throw InputError(plan.declaration.origin + ": sweep parameter '" + name +
                       "': the name of a column manifest.csv writes for every point (" + list +
                       "): choose another name (e.g. " + name + "_value)");
    }
}

}  // namespace

SweepOutcome runSweep(const SweepRun& cmd) {
  const auto defines = parseDefines(cmd.args.defines);
  renderOptions(cmd.args, 0);  // validate the sampling options before any work
  const LayerSet layers = LayerSet::parse(cmd.layers);
  const bool numbered = !cmd.frames.empty();
  const FrameOrder order = referenceFirst(numbered ? parseFrames(cmd.frames) : std::vector<int>{0}, cmd.referenceFrame);
  const std::vector<int>& frames = order.frames;
  const SweepPlan plan = planSweep(cmd.args.scenePath, defines, cmd.sweep);
  checkManifestColumns(plan);
  const Shard shard = resolveShard(cmd.shard);

  if (cmd.list) {
    // This shard's points (--shard or Slurm's variables), as the run would render them.
    for (std::int64_t i = shard.index; i < plan.count; i += shard.count) {
      const SweepPoint p = plan.point(i);
      std::printf("%lld %s", (long long)p.index, pointFolderName(p.index).c_str());
      for (const auto& [name, value] : p.values) std::printf(" %s=%s", name.c_str(), value.defineText().c_str());
      std::printf("\n");
    }
    return {};
  }

  // The key of a point: everything that determines its files. The scene enters by its content
  // (CRC-32), so editing the scene invalidates finished points; assets it loads do not enter.
  const std::uint32_t sceneCrc32 = crc32Of(readWholeFile(cmd.args.scenePath));
  // -D values and --frames as the scene receives them, not as typed: -D gain=0.50 after gain=0.5,
  // the -D options in another order, --frames 00:1 or the default --reference-frame given did
  // render every point again and made --merge-only refuse (sweep audit, 2026-11-28). Canonical
  // forms are the usual spellings, so keys of earlier sweeps stay the same.
  std::vector<std::pair<std::string, std::string>> sortedDefines = defines;
  std::sort(sortedDefines.begin(), sortedDefines.end());
  std::string definesText;
  for (const auto& [n, v] : sortedDefines) definesText += n + "=" + canonicalDefineText(v) + " ";
  std::string framesText;
  if (numbered) {
    const std::vector<int> given = parseFrames(cmd.frames);
    framesText = given.size() == 1 ? std::to_string(given[0])
                                   : std::to_string(given.front()) + ":" + std::to_string(given.back());
    if (cmd.referenceFrame && *cmd.referenceFrame != given.front())
      framesText += " reference " + std::to_string(*cmd.referenceFrame);
  } else if (cmd.referenceFrame && *cmd.referenceFrame != 0) {
    framesText = "0 reference " + std::to_string(*cmd.referenceFrame);
  }  // without --frames and --reference-frame, frame 0 is the only frame and the reference
  const KeyFields commonFields = {
      {"scene_crc32", std::to_string(sceneCrc32)},
      {"spp", std::to_string(cmd.args.spp)},
      {"precision", cmd.args.precision},
      {"max_error_px", exactNumber(cmd.args.maxErrorPx)},
      {"downscale", std::to_string(cmd.args.downscale)},
      {"backend", cmd.backend},
      // The reference frame only when it is not the first: the keys of sweeps made before the
      // option stay the same.
      {"frames", framesText},
      {"defines", definesText},
      {"exr_compression", cmd.exrCompression},
      {"layers", layers.text()}};
  const std::string commonKey = joinKey(commonFields);
  // The manifest's "run": the common fields, and the random draw when --random gave the points.
  KeyFields runFields = commonFields;
  for (auto& [name, value] : runFields)  // as the EXR and TIFF write it (the key keeps its decimal)
    if (name == "scene_crc32") {
      char hex[16];
      std::snprintf(hex, sizeof hex, "%08x", unsigned(sceneCrc32));
      value = hex;
    }
  // The seed options: each point's seed is listed, but not how it came (the cluster trial of
  // 2026-11-29: the manifest is to say how to make the sweep again).
  runFields.emplace_back("seed", std::to_string(cmd.args.seed));
  runFields.emplace_back("seed_per_point", cmd.seedPerPoint ? "true" : "false");
  if (cmd.sweep.randomCount)
    runFields.emplace_back("random", std::to_string(*cmd.sweep.randomCount) + " points, seed " + std::to_string(cmd.sweep.randomSeed));
  auto seedOf = [&](const SweepPoint& p) {
    return cmd.seedPerPoint ? ds_hash_combine(ds_hash(cmd.args.seed), std::uint32_t(p.index)) : cmd.args.seed;
  };
  auto pointFields = [&](const SweepPoint& p) {
    return KeyFields{{"seed", std::to_string(seedOf(p))}, {"parameters", parametersJson(p)}};
  };
  // The key of every point (the manifest checks millions): the common part joined once.
  auto keyOf = [&](const SweepPoint& p) { return commonKey + " " + joinKey(pointFields(p)); };
  auto keyFieldsOf = [&](const SweepPoint& p) {  // for messages
    KeyFields fields = commonFields;
    for (auto& field : pointFields(p)) fields.push_back(std::move(field));
    return fields;
  };

  // Before anything is created: the output folder can be written, and the first point's scene
  // evaluates (a --sweep value the scene cannot take, e.g. a string for a coordinate, stops here).
  // --merge-only reads what is there: a folder that does not exist is a mistyped -o, not an empty sweep.
  if (cmd.mergeOnly && !fs::is_directory(cmd.outputDir))
    throw InputError("-o " + cmd.outputDir + ": no such folder: --merge-only merges the points of an existing sweep");
  checkOutputWritable(cmd.outputDir);
  std::uint64_t firstPointBytes = 0;  // its rendered frames until written (a point's size, for the writers)
  // Every frame of the first point: a parameter may be read in some frames only.
  UnreadDefines unread;
  try {
    LayerSources sources;  // a layer the first point cannot produce is refused before the folder is made
    for (const int frame : frames) {
      SceneParams first{pointDefines(defines, plan.point(0)), frame};
      first.sweepParameters = plan.names;
      first.quiet = true;  // a check: the point's own evaluation prints when it renders
      first.requireDefinesRead = false;
      const Scene scene = loadScene(cmd.args.scenePath, first);
      unread.add(scene);
      sources.add(scene);
      firstPointBytes += framePixels(scene, cmd.args.downscale) * kBytesPerPixelInFlight;
    }
    checkLayersProducible(layers, sources);
  } catch (const InputError& e) {
    // The point's scene or layers, named as a later point's error is: `--layers noise` refused
    // where the first point's value turns the sensor model off read as the sweep's own refusal (the
    // calibration trial of 2026-11-28).
    throw InputError(std::string(e.what()) + " (sweep point " + pointFolderName(0) + ": " + pointValues(plan.point(0)) +
                     ", evaluated before any work)");
  }
  unread.check(cmd.args.scenePath, plan.names);  // of the parameters, whatever the point
  createOutputDir(cmd.outputDir);  // writable: checkOutputWritable created a file where it goes
  // A killed run's partial manifests (.manifest.csv.tmp<pid>_<n>.csv): the points' own are removed
  // when a point is rendered again, these here.
  removeStaleTemporaries(cmd.outputDir);
  sweep::AssetChecksums assets;
  const sweep::PointsBeyond beyond = sweep::finishedPointsBeyond(cmd.outputDir, plan.count);
  const std::string beyondText = "-o " + cmd.outputDir + " holds " + std::to_string(beyond.count) + " finished point" +
                                 (beyond.count == 1 ? "" : "s") + " beyond this sweep's " + std::to_string(plan.count) +
                                 " (" + beyond.text() + "), of a larger sweep";
  if (cmd.mergeOnly) {
    // A smaller sweep's manifest would not list them: refused like points of other inputs.
    if (beyond.count > 0)
      throw InputError("sweep --merge-only: " + beyondText +
                       ": a manifest of these points would not list them. Give the --sweep options (or the scene) the "
                       "sweep was run with (the manifest is left as it was)");
    // A point made with other options (a forgotten --spp, another scene) would silently drop out of
    // the manifest, and a good manifest be replaced by a shorter one: refused, the manifest untouched.
    // Checksums verified: a merge after shards (a Slurm job's last step) must not list a damaged point.
    const auto summary = sweep::writeManifest(
        cmd.outputDir, cmd.args.scenePath, runFields, plan, keyOf, assets, true, [&](const SweepPoint& p, const sweep::PointRecord& r) {
          throw InputError("sweep --merge-only: " + pointFolderName(p.index) + " was rendered with other inputs: " +
                           keyDifference(r.key, keyFieldsOf(p)) +
                           ". Give the options the sweep was run with (the manifest is left as it was), or run the "
                           "sweep without --merge-only to render such points again");
        });
    std::printf("manifest: %lld of %lld points complete (%s/manifest.csv, manifest.json)%s\n",
                (long long)summary.complete, (long long)summary.total, cmd.outputDir.c_str(), missingText(summary).c_str());
    warnMixedDevices(summary);
    warnMixedBuilds(summary);
    return {summary.complete, summary.total};
  }
  const fs::path lockDir = fs::path(cmd.outputDir) / ".locks";
  std::error_code ec;
  fs::create_directories(lockDir, ec);
  if (ec) throw InputError("-o " + cmd.outputDir + ": cannot create " + lockDir.string() + ": " + ec.message());

  // What makes this run's points: the common key (the scene's content, which holds a declared
  // sweep, the -D values and the options), the --sweep/--random options as given (a listed value
  // changed in the middle changes no end point), and the keys of the first, middle and last points.
  // Shards and reruns of one sweep share it.
  std::string runKey = std::to_string(plan.count) + "\n" + keyOf(plan.point(0)) + "\n" +
                       keyOf(plan.point(plan.count / 2)) + "\n" + keyOf(plan.point(plan.count - 1)) + "\n";
  for (const std::string& s : cmd.sweep.sweeps) runKey += "--sweep " + s + "\n";
  if (cmd.sweep.randomCount)
    runKey += "--random " + std::to_string(*cmd.sweep.randomCount) + " " + std::to_string(cmd.sweep.randomSeed) + "\n";
  char fingerprint[16];
  std::snprintf(fingerprint, sizeof fingerprint, "%08x", unsigned(crc32Of(runKey)));
  const sweep::RunLock runLock(lockDir, fingerprint, cmd.outputDir);

  // A larger sweep's points stay where they are, but the manifest lists this sweep's: said before
  // any point (the cluster trial of 2026-11-29 reran an 8-point sweep into a 300-point folder: an
  // "8 of 8 complete" manifest beside 292 unlisted points, without a word).
  if (beyond.count > 0)
    warn(beyondText + ", which stay and which the manifest does not list: the folder mixes two sweeps (write each "
         "sweep into a folder of its own)");

  // This shard's points: index ≡ shard.index (mod shard.count).
  const std::int64_t mine = plan.count > shard.index ? (plan.count - shard.index + shard.count - 1) / shard.count : 0;

  // --keep-finished: a finished point made with other inputs stops the run before any point renders
  // (a resubmitted cluster job with a forgotten option replaced every finished point, --strict only
  // failing afterwards: the cluster trial of 2026-11-29).
  if (cmd.keepFinished)
    for (std::int64_t index = shard.index; index < plan.count; index += shard.count) {
      const SweepPoint p = plan.point(index);
      const auto recorded = sweep::readPointRecord((fs::path(cmd.outputDir) / pointFolderName(p.index)).string());
      if (!recorded || recorded->index != p.index) continue;
      if (recorded->key != keyOf(p))
        throw InputError("sweep --keep-finished: " + pointFolderName(p.index) + " was rendered with other inputs (" +
                         keyDifference(recorded->key, keyFieldsOf(p)) +
                         "): nothing is rendered. Give the options the sweep was run with, or run without "
                         "--keep-finished to render such points again");
      // Its inputs also hold the textures and meshes it loaded, which a resubmitted job may have
      // remade (the review of 2026-11-29: a rewritten speckle.tif replaced every finished point).
      // Its own files damaged or missing is a point to finish, as ever.
      if (const auto change = sweep::changedAsset(*recorded, assets))
        throw InputError("sweep --keep-finished: " + pointFolderName(p.index) + " was rendered from " + change->path +
                         ", which " + change->what + ": nothing is rendered. Restore the file, or run without "
                         "--keep-finished to render the points that used it again");
    }

  RenderSession session(cmd.args, cmd.backend);
  Progress progress(mine, stderrIsTerminal());
  std::int64_t done = 0, rendered = 0, skipped = 0, busy = 0, images = 0;
  std::int64_t replaced = 0;  // finished points of other inputs, rendered again
  std::int64_t damaged = 0;   // finished points whose textures or files changed, rendered again
  const std::string host = hostName();
  // The files of a point are written (sensor, truth, files, record) on a worker thread while the
  // main thread evaluates, prepares and renders the next: at most outputWriters() points wait to be
  // written, so memory does not grow with the number of points.
  WorkerPool writers(outputWriters(firstPointBytes));
  // Counts the points written since the last call; `all`: waits for every one, else for a free writer.
  // Rethrows a writer's error.
  auto collectWritten = [&](bool all) {
    for (std::size_t n = all ? writers.waitAll() : writers.waitForFree(); n > 0; --n) {
      ++rendered;
      progress.update(++done, skipped + busy, images);
    }
  };
  for (std::int64_t index = shard.index; index < plan.count; index += shard.count) {
    const SweepPoint p = plan.point(index);
    const std::string folder = (fs::path(cmd.outputDir) / pointFolderName(p.index)).string();
    // One owner per point at a time, whatever the sharding: a second process skips it.
    auto lock = std::make_shared<sweep::FileLock>((lockDir / (pointFolderName(p.index) + ".lock")).string(), false);
    if (!lock->acquired()) {
      ++busy;
      progress.update(++done, skipped + busy, images);
      continue;
    }
    const std::string key = keyOf(p);
    const auto recorded = sweep::readPointRecord(folder);
    std::string why;
    if (recorded && recorded->index == p.index && sweep::pointFilesIntact(folder, *recorded, key, true, assets, &why)) {
      ++skipped;
      progress.update(++done, skipped + busy, images);
      continue;
    }
    // A finished point whose texture changed or whose files were damaged is rendered again: said
    // once (the sweep audit met points re-rendered without a word after a texture was edited).
    if (recorded && recorded->index == p.index && recorded->key == key && damaged++ == 0)
      warn(pointFolderName(p.index) + " is rendered again: " + why +
           " (as is every finished point whose textures, meshes or files are not as recorded)");
    // A finished point made with other inputs is rendered again (its files replaced): said once, with
    // what differs, since a forgotten option would otherwise replace a whole sweep unnoticed.
    if (recorded && recorded->index == p.index && recorded->key != key && replaced++ == 0) {
      warn(pointFolderName(p.index) + " was rendered with other inputs (" +
           keyDifference(recorded->key, keyFieldsOf(p)) +
           "): it is rendered again, as is every point whose record differs (stop now to keep them, and rerun with "
           "the options they were made with); the manifest, which lists the points as they were, is removed until "
           "this run rebuilds it");
      sweep::removeManifest(cmd.outputDir);
    }
    auto job = std::make_shared<RenderJob>();
    job->sceneFile = cmd.args.scenePath;
    job->outputDir = folder;
    job->frames = frames;
    job->writeReference = order.referenceWritten;
    job->numbered = numbered;
    job->defines = pointDefines(defines, p);
    job->sweepParameters = plan.names;
    job->requireDefinesRead = false;  // checked at the first point, before work
    job->seed = seedOf(p);
    job->verbose = false;
    job->exrCompression = cmd.exrCompression;
    job->layers = layers;
    job->sceneCrc32 = sceneCrc32;  // the content the point's key names
    RenderedJob result;
    try {
      try {
        result = renderJob(session, *job);
      } catch (const InputError& e) {
        // Only the first point is evaluated before work: a later point's scene error stops the run
        // here, the points before it complete. The message names the point (the sweep audit met a
        // bare "scene.lua:2: negative shift" after two points were written).
        throw InputError(std::string(e.what()) + " (sweep point " + pointFolderName(p.index) + ": " + pointValues(p) +
                         "; the points rendered before it are complete, and a rerun resumes after the fix)");
      }
    } catch (...) {
      collectWritten(true);  // the points being written still complete (a writer's error, if any, wins)
      throw;
    }
    for (std::size_t fi = job->firstWrittenIndex(); fi < result.frames.size(); ++fi)
      images += std::int64_t(result.frames[fi].result.cameras.size());
    collectWritten(false);
    // Not complete: the point starts from an empty folder (a killed run may have left part of it).
    std::error_code ec;
    fs::remove_all(folder, ec);
    auto record = std::make_shared<sweep::PointRecord>();
    record->index = p.index;
    record->key = key;
    record->parametersJson = parametersJson(p);
    record->seed = seedOf(p);
    record->samplesPerPixel = cmd.args.spp;
    record->backend = result.summary.backend;
    record->precision = result.summary.precision;
    record->device = result.summary.device;
    record->renderSeconds = result.summary.renderSeconds;
    record->host = host;
    record->build = codeBuildIdText();
    // The textures it rendered with, so that a rerun notices when they change: the CRC-32 of the
    // bytes each was decoded from (PreparedTexture::contentCrc32), not of the file after the render.
    // A texture whose content changed while the point rendered stops the run, the point unrecorded:
    // its record would hold a content no longer there, and the points after it another (the faults
    // audit of 2026-11-28 found such points recorded with the new file's CRC over an image of the
    // old one, 7 of 10 trials). The same bytes under a new stamp (a touch, a copy over it, another
    // shard writing the same seeded texture again) are the content rendered: the run goes on (it
    // stopped before).
    // The meshes of Field.load fields likewise (a rerun of the FE simulation rewrites them): before
    // 2026-11-28 a point did not record them, and a sweep run again after the mesh changed took its
    // points, made with the old field, as complete.
    std::vector<sweep::PointFile> rendered;
    for (const RenderedFrame& f : result.frames)
      forEachInputFile(f.scene, [&](const char* kind, const FileContent& file) {
        if (!fileStillHolds(file.path, file.stamp, file.crc32)) {
          collectWritten(true);
          throw InputError(file.path + ": the " + kind + " file changed while sweep point " + pointFolderName(p.index) +
                           " rendered (the point is not recorded; a rerun renders it, and the points after it, with the "
                           "file as it is then)");
        }
        rendered.push_back(assets.known(file.path, file.stamp, file.crc32));
      });
    record->assets = sweep::AssetChecksums::listed(std::move(rendered));
    writers.start([job, record, lock, folder, r = std::make_shared<RenderedJob>(std::move(result))] {
      try {
        writeRenderedJob(std::move(*r), *job);
        record->files = sweep::scanPointFiles(folder);
        record->finishedUtc = utcNow();
        sweep::writePointRecord(folder, *record);  // last: the point is complete from here on
      } catch (...) {
        std::error_code ignored;
        fs::remove_all(folder, ignored);  // nothing half-written stays (and a full disk gets its space back)
        throw;
      }
    });
  }
  collectWritten(true);
  const auto summary = sweep::writeManifest(cmd.outputDir, cmd.args.scenePath, runFields, plan, keyOf, assets, false);
  warnMixedDevices(summary);
  warnMixedBuilds(summary);
  const std::string replacedText =
      replaced ? " (" + std::to_string(replaced) + " of them replacing points rendered with other inputs)" : "";
  std::printf("sweep: %lld points%s: rendered %lld%s, already complete %lld, in progress elsewhere %lld; "
              "manifest: %lld of %lld points complete (%s/manifest.csv, manifest.json)\n",
              (long long)mine,
              shard.count > 1 ? (" (shard " + std::to_string(shard.index) + "/" + std::to_string(shard.count) + " of " +
                                 std::to_string(plan.count) + ", by " + shard.origin + ")").c_str()
                              : "",
              (long long)rendered, replacedText.c_str(), (long long)skipped, (long long)busy, (long long)summary.complete,
              (long long)summary.total, cmd.outputDir.c_str());
  return {summary.complete, summary.total};
}


}  // namespace dicsynth
