#include "hqview/pipeline/batch.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include <tbb/task_arena.h>

#include "hqview/core/error.h"
#include "hqview/core/error_kind.h"
#include "hqview/core/sha256.h"
#include "hqview/core/stop.h"
#include "hqview/core/text.h"
#include "hqview/io/mesh_reader.h"
#include "hqview/render/upright.h"
#include "hqview/report/json_path.h"
#include "hqview/report/link_base.h"
#include "hqview/report/report_json.h"

namespace hq {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// --resume: the bundle's report.json names the same HQView version and the
// same mesh, reference and compare mesh bytes (SHA-256) as this run would.
bool is_resumable(const BatchInput& input, const fs::path& report_path, const std::string& tool_version) {
  std::error_code ec;
  if (!fs::is_regular_file(report_path, ec)) return false;
  const json old = json::parse(read_file_bytes(report_path), nullptr, false);
  if (old.is_discarded() || !old.is_object()) return false;
  const json tool = old.value("tool", json::object());
  if (!tool.is_object() || tool.value("version", "") != tool_version) return false;
  auto old_sha = [&](const char* which) {
    const json in = old.value("input", json::object());
    return in.is_object() && in.contains(which) && in[which].is_object() ? in[which].value("sha256", "")
                                                                         : std::string();
  };
  auto sha_of = [](const fs::path& file) {
    return file.empty() ? std::string() : sha256_file_hex(file).value_or(std::string());
  };
  return old_sha("mesh") == sha_of(input.mesh_file) && old_sha("reference") == sha_of(input.reference_file) &&
         old_sha("compare") == sha_of(input.compare_file);
}

}  // namespace

int shard_of(std::string_view path, int count) {
  // The first 8 bytes of SHA-256: the same on every machine and compiler.
  const std::string hex = sha256_hex(path);
  std::uint64_t h = 0;
  for (int i = 0; i < 16; ++i) {
    const char c = hex[static_cast<std::size_t>(i)];
    h = h * 16 + static_cast<std::uint64_t>(c <= '9' ? c - '0' : c - 'a' + 10);
  }
  return static_cast<int>(h % static_cast<std::uint64_t>(count)) + 1;
}

std::vector<BatchInput> select_shard(const std::vector<BatchInput>& inputs, const Shard& shard) {
  std::vector<BatchInput> selected;
  for (const BatchInput& input : inputs)
    if (shard_of(input.path, shard.count) == shard.index) selected.push_back(input);
  return selected;
}

BatchEntry run_batch_mesh(const BatchInput& input, const BatchOptions& options, bool& is_resumed) {
  is_resumed = false;
  BatchEntry entry;
  entry.path = input.path;
  entry.label = input.label;
  entry.model = input.model;
  entry.variant = input.variant;
  entry.paper = input.paper;
  if (!input.skip_reason.empty()) {
    entry.status = BatchStatus::skipped;
    entry.error = input.skip_reason;
    return entry;
  }
  const fs::path dir = options.output / fs::path(input.path);
  try {
    if (options.resume && is_resumable(input, dir / "report.json", options.analyze.tool_version)) {
      const ReportDocument report = ReportDocument::parse(read_file_bytes(dir / "report.json"));
      fill_entry_from_report(entry, report);
      // The rules of this run decide the status, not those of the kept bundle.
      if (!options.analyze.gates.empty()) {
        const GateSummary gates = evaluate_gates(options.analyze.gates, report);
        entry.gates = gates.results;
        entry.failed_gates.clear();
        for (const GateResult& g : gates.results)
          if (!g.passed) entry.failed_gates.push_back(g.rule);
        entry.status = gates.passed ? BatchStatus::ok : BatchStatus::gate_failed;
      }
      entry.bundle = input.path;
      is_resumed = true;
      return entry;
    }
    AnalyzeOptions analyze_options = options.analyze;
    analyze_options.mesh_path = input.mesh_file;
    analyze_options.reference_path = input.reference_file;
    analyze_options.compare_path = input.compare_file;
    analyze_options.limitations_as_warnings = true;  // a limitation is no failure: the rest is analysed
    // The manifest's up column: an axis, or auto (the resting axis).
    if (input.up == "auto") {
      analyze_options.up_auto = true;
    } else if (!input.up.empty()) {
      analyze_options.up_auto = false;
      analyze_options.views.up = *parse_up_axis(input.up);
    }
    BundleOptions bundle;
    bundle.force = options.force;
    bundle.link_base = link_base_of(options.link_base, input.path);
    bundle.single_file = options.single_file;
    check_output_dir(dir, bundle);
    // The mesh's work stays on its own: a thread waiting inside it runs only
    // its tasks, so that the deadline it checks is this mesh's (stop.h).
    tbb::this_task_arena::isolate([&] {
      std::optional<stop::ScopedDeadline> deadline;
      if (options.mesh_timeout > 0) deadline.emplace(options.mesh_timeout, "--mesh-timeout");
      const std::unique_ptr<Renderer> renderer = options.make_renderer ? options.make_renderer() : nullptr;
      const AnalyzeResult result = analyze(analyze_options, renderer.get());
      write_bundle(result.model, result.document, result.images, dir, bundle);
      fill_entry_from_report(entry, result.document);
      if (!options.analyze.gates.empty()) entry.gates = evaluate_gates(options.analyze.gates, result.document).results;
    });
    entry.bundle = input.path;
  } catch (const std::exception& e) {
    const ErrorKind kind = kind_of_current_exception();
    if (kind == ErrorKind::interrupted) throw;  // the whole batch stops (run_batch)
    entry.status = BatchStatus::failed;
    entry.environment_failure = kind == ErrorKind::environment;
    // hq::Error's messages (a render failure, a timeout) stand as they are;
    // a std:: exception from elsewhere is a bug.
    entry.error = dynamic_cast<const std::bad_alloc*>(&e) != nullptr ? std::string("out of memory")
                  : dynamic_cast<const Error*>(&e) == nullptr        ? std::string("internal error: ") + e.what()
                                                                     : std::string(e.what());
  }
  if (entry.status == BatchStatus::failed) {
    entry.bundle.clear();
    entry.failed_gates.clear();
    entry.gates.clear();
    entry.headline.assign(kNumHeadlineKeys, std::nullopt);
    // Hashed in chunks: a failed mesh may be a file too big to read whole.
    std::error_code ec;
    entry.sha256 = fs::is_regular_file(input.mesh_file, ec) ? sha256_file_hex(input.mesh_file).value_or("") : "";
  }
  return entry;
}

std::vector<BatchEntry> run_batch(const std::vector<BatchInput>& inputs, const BatchOptions& options,
                                  BatchProgress* progress) {
  std::vector<BatchEntry> entries(inputs.size());
  std::vector<std::uint64_t> cost(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    std::error_code ec;
    std::uint64_t size = fs::file_size(inputs[i].mesh_file, ec);
    if (ec) size = 0;
    // A compare mesh is analysed in the same run: count its bytes too.
    if (!inputs[i].compare_file.empty())
      if (const auto other = fs::file_size(inputs[i].compare_file, ec); !ec) size += other;
    cost[i] = estimate_mesh_memory(size, static_cast<bool>(options.make_renderer), options.analyze.simulate);
  }
  const int workers = std::clamp(options.jobs, 1, std::max(1, static_cast<int>(inputs.size())));
  // Meshes analysed side by side each draw their views on one thread (their
  // parallelism is the batch's); a batch of one worker draws on two.
  BatchOptions per_mesh = options;
  if (workers > 1) per_mesh.analyze.views.render_threads = 1;
  std::mutex mutex;
  std::condition_variable released;
  std::uint64_t in_flight = 0;
  int running = 0;
  int done = 0;
  std::size_t next = 0;
  const int total = static_cast<int>(inputs.size());
  std::exception_ptr interrupted;  // the first Interrupted: no mesh starts after it

  auto worker = [&] {
    while (true) {
      std::size_t i = 0;
      {
        std::unique_lock lock(mutex);
        if (next >= inputs.size() || interrupted || stop::requested() != 0) return;
        i = next++;
        // A mesh starts when it fits in the budget next to those running, or
        // runs alone (a mesh larger than the budget still gets analysed).
        // Woken every 100 ms to notice a signal.
        while (!released.wait_for(lock, std::chrono::milliseconds(100), [&] {
          return options.memory_budget == 0 || running == 0 || in_flight + cost[i] <= options.memory_budget;
        }))
          if (stop::requested() != 0) return;
        in_flight += cost[i];
        ++running;
        if (progress) progress->mesh_started(inputs[i]);
      }
      const auto start = std::chrono::steady_clock::now();
      bool is_resumed = false;
      bool stopped = false;
      try {
        entries[i] = run_batch_mesh(inputs[i], per_mesh, is_resumed);
      } catch (const Interrupted&) {
        stopped = true;
        const std::lock_guard lock(mutex);
        if (!interrupted) interrupted = std::current_exception();
      }
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      {
        std::lock_guard lock(mutex);
        in_flight -= cost[i];
        --running;
        if (!stopped) {
          ++done;
          if (progress) progress->mesh_finished(entries[i], is_resumed, seconds, done, total);
        }
      }
      released.notify_all();
      if (stopped) return;
    }
  };
  std::vector<std::thread> threads;
  for (int t = 1; t < workers; ++t) threads.emplace_back(worker);
  worker();
  for (std::thread& t : threads) t.join();
  if (interrupted) std::rethrow_exception(interrupted);
  if (const int signal = stop::requested(); signal != 0) throw Interrupted(signal);
  std::sort(entries.begin(), entries.end(), [](const BatchEntry& a, const BatchEntry& b) { return a.path < b.path; });
  return entries;
}

std::vector<BatchEntry> merge_shards(const std::vector<fs::path>& shard_dirs, const fs::path& out) {
  std::map<std::string, BatchEntry> merged;
  std::map<std::string, fs::path> source;
  for (const fs::path& shard : shard_dirs) {
    const fs::path index = shard / "index.json";
    std::ifstream in(index, std::ios::binary);
    if (!in) throw InputError(index.string() + ": cannot open (not a batch output directory?)");
    std::ostringstream text;
    text << in.rdbuf();
    for (BatchEntry& e : parse_batch_index_json(text.str(), index.string())) {
      if (merged.count(e.path))
        throw InputError(index.string() + ": mesh '" + e.path + "' is also in " + source[e.path].string() +
                         " (shards overlap)");
      source[e.path] = shard;
      merged.emplace(e.path, std::move(e));
    }
  }
  fs::create_directories(out);
  std::vector<BatchEntry> entries;
  for (auto& [path, e] : merged) {
    if (!e.bundle.empty()) {
      const fs::path from = source[path] / fs::path(e.bundle);
      const fs::path to = out / fs::path(e.bundle);
      if (fs::weakly_canonical(from) != fs::weakly_canonical(to)) {
        if (!fs::is_regular_file(from / "report.json"))
          throw InputError(from.string() + ": the bundle listed in the shard's index.json is missing");
        fs::create_directories(to.parent_path());
        std::error_code ignored;
        fs::remove_all(to, ignored);
        fs::copy(from, to, fs::copy_options::recursive);
      }
    }
    entries.push_back(std::move(e));
  }
  return entries;
}

}  // namespace hq
