#include "hqview/report/bundle_writer.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

#include <tbb/parallel_for.h>

#include <nlohmann/json.hpp>

#include "hqview/core/error.h"
#include "hqview/core/fault_point.h"
#include "hqview/core/stop.h"
#include "hqview/report/atomic_file.h"
#include "hqview/image/png.h"
#include "hqview/report/link_base.h"
#include "hqview/report/report_csv.h"
#include "hqview/report/report_html.h"
#include "hqview/report/report_json.h"
#include "hqview/report/report_markdown.h"
#include "hqview/report/report_vtu.h"
#include "hqview/report/viewer.h"

namespace hq {
namespace fs = std::filesystem;
namespace {

bool is_bundle(const fs::path& dir) { return fs::is_regular_file(dir / "report.json"); }

bool is_inside_bundle(const std::string& relative_path) {
  const fs::path p(relative_path);
  if (p.empty() || p.is_absolute() || p.has_root_name()) return false;
  for (const fs::path& part : p)
    if (part == ".." || part == "." || part.empty()) return false;
  return true;
}

template <class WriteFn>
void write_file(const fs::path& path, WriteFn&& write) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  if (!out) throw EnvironmentError(path.string() + ": cannot create: " + std::strerror(errno));
  try {
    write(out);
  } catch (const std::system_error& e) {  // a write that failed on a worker thread (throw_if_failed)
    throw EnvironmentError(path.string() + ": write failed: " + e.code().message());
  }
  out.flush();
  if (!out) throw EnvironmentError(path.string() + ": write failed: " + std::strerror(errno));
}

void write_text(const fs::path& path, std::string_view text) {
  write_file(path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

// "path: cause" of a file system error, the cause as the OS says it.
std::string describe(const fs::filesystem_error& e) {
  std::string out = e.path1().empty() ? std::string() : e.path1().string() + ": ";
  return out + e.code().message();
}

// The process that named a temporary `.NAME.TAG-PID` is gone (a run that was
// killed): its leftovers may be removed.
bool is_stale(const std::string& name, std::string_view tag, std::string& base) {
  if (name.size() < 2 || name[0] != '.') return false;
  const std::size_t at = name.rfind(std::string(".") + std::string(tag) + "-");
  if (at == std::string::npos || at == 0) return false;
  const std::string pid_text = name.substr(at + tag.size() + 2);
  if (pid_text.empty() || pid_text.size() > 9 || pid_text.find_first_not_of("0123456789") != std::string::npos)
    return false;
  const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
  if (pid == ::getpid() || pid <= 0) return false;
  if (::kill(pid, 0) == 0 || errno == EPERM) return false;  // still running
  base = name.substr(1, at - 1);
  return true;
}

}  // namespace

void swap_into_place(const fs::path& tmp, const fs::path& dir) {
  // Exchanged in one step where the file system can (Linux renameat2): there
  // is never a moment without a bundle at DIR, and two runs writing DIR at
  // once each put a whole bundle there; the last one stays.
  if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, dir.c_str(), RENAME_NOREPLACE) == 0) return;
  if (errno == EEXIST || errno == ENOTEMPTY) {
    if (::renameat2(AT_FDCWD, tmp.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
      std::error_code ignored;
      fs::remove_all(tmp, ignored);  // now the old bundle
      return;
    }
  }
  // ENOENT: DIR vanished between the two calls; EINVAL/ENOSYS: no renameat2
  // flags on this file system. Both: the two renames below.
  if (errno != ENOENT && errno != EINVAL && errno != ENOSYS)
    throw EnvironmentError(dir.string() + ": cannot put the new bundle in place: " + std::strerror(errno));
  // The old bundle is moved aside, never deleted before the new one is in
  // place; a run killed in between leaves it as `.DIR.hqview-old-PID`, which
  // the next run puts back (remove_stale_temporaries).
  if (fs::exists(dir)) {
    const fs::path old = temporary_sibling(dir, kSetAsideTag);
    fs::remove_all(old);
    fs::rename(dir, old);
    try {
      fs::rename(tmp, dir);
    } catch (...) {
      fs::rename(old, dir);
      throw;
    }
    fs::remove_all(old);
  } else {
    fs::rename(tmp, dir);
  }
}

int remove_stale_temporaries(const fs::path& dir, bool recursive) {
  int removed = 0;
  std::error_code ec;
  std::vector<fs::path> subdirs;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::string base;
    std::error_code ignored;
    if (is_stale(name, kTemporaryTag, base)) {
      fs::remove_all(it->path(), ignored);
      ++removed;
    } else if (is_stale(name, kSetAsideTag, base)) {
      // A killed swap: the bundle it moved aside goes back where it was.
      const fs::path original = dir / base;
      if (!fs::exists(fs::symlink_status(original, ignored)))
        fs::rename(it->path(), original, ignored);
      else
        fs::remove_all(it->path(), ignored);
      ++removed;
    } else if (recursive && name[0] != '.' && it->is_directory(ignored) && !it->is_symlink(ignored)) {
      subdirs.push_back(it->path());
    }
  }
  for (const fs::path& sub : subdirs)
    if (!fs::is_regular_file(sub / "report.json", ec)) removed += remove_stale_temporaries(sub, true);
  return removed;
}

std::string timings_json(const std::vector<StageTime>& timings, double wall_seconds) {
  nlohmann::json stages = nlohmann::json::array();
  double total = 0.0;
  for (const StageTime& t : timings) {
    stages.push_back(
        {{"name", t.name}, {"seconds", t.seconds}, {"peak_rss_mb", std::round(t.peak_rss_bytes / 1e5) / 10}});
    if (t.concurrent)
      stages.back()["concurrent"] = true;
    else
      total += t.seconds;
  }
  const nlohmann::json j = {
      {"note", "wall seconds of this run's stages; differs from run to run (report.json does not)"},
      {"stages", std::move(stages)},
      {"total_seconds", total},
      {"wall_seconds", wall_seconds}};
  return j.dump(2) + "\n";
}

namespace {

// report.html from the pages, stylesheet, images and viewer written in `dir`.
std::string single_file_of(const fs::path& dir, const BundleOptions& options) {
  auto read = [&dir](const std::string& relative) -> std::optional<std::string> {
    if (!is_inside_bundle(relative)) return std::nullopt;
    std::ifstream in(dir / relative, std::ios::binary);
    if (!in) return std::nullopt;
    std::ostringstream text;
    text << in.rdbuf();
    return std::move(text).str();
  };
  const std::optional<std::string> index = read("index.html"), boundary = read("boundary.html"),
                                   viewer = read("viewer.html"), css = read("style.css");
  const std::string index_text = index.value_or(""), css_text = css.value_or("");
  SingleFileSources sources;
  sources.index_html = index_text;
  if (boundary) sources.boundary_html = *boundary;
  if (viewer && options.single_file == SingleFile::viewer) sources.viewer_html = *viewer;
  sources.stylesheet = css_text;
  sources.read_file = read;
  sources.link_base = options.link_base;
  return single_file_html(sources);
}

}  // namespace

void check_output_dir(const fs::path& dir, const BundleOptions& options) {
  std::error_code ec;
  const auto status = fs::symlink_status(dir, ec);
  if (ec || !fs::exists(status)) return;
  if (!fs::is_directory(status)) {
    if (!options.force)
      throw ValueError(dir.string() + ": exists and is not a directory; choose another -o, or --force to replace it");
    return;
  }
  if (!options.force && !fs::is_empty(dir) && !is_bundle(dir))
    throw ValueError(dir.string() +
                     ": is a non-empty directory that is not an HQView bundle (no report.json); "
                     "use --force to replace it");
}

void write_bundle(const ReportModel& model, const ReportDocument& document, const std::vector<BundleImage>& images,
                  const fs::path& target, const BundleOptions& options) {
  const fs::path dir = fs::absolute(target).lexically_normal();
  check_output_dir(dir, options);
  try {
    fs::create_directories(dir.parent_path());
  } catch (const fs::filesystem_error& e) {
    throw EnvironmentError("writing the bundle: " + describe(e));
  }
  remove_stale_temporaries(dir.parent_path(), false);
  const fs::path tmp = temporary_sibling(dir, kTemporaryTag);
  std::error_code ignored_ec;
  fs::remove_all(tmp, ignored_ec);
  // Every file stays inside the bundle: image paths are relative, without "..".
  for (const BundleImage& img : images)
    if (!is_inside_bundle(img.relative_path))
      throw Error("internal: bundle file outside the bundle: " + img.relative_path);
  std::vector<StageTime> timings = model.analysis.timings;
  try {
    StageClock clock(timings, options.on_stage);
    fs::create_directories(tmp / "data");
    clock.start("write report.json");
    write_text(tmp / "report.json", report_json_text(document));
    clock.start("write pages");
    write_text(tmp / "index.html", absolute_links_html(index_html(model), options.link_base));
    write_text(tmp / "style.css", report_stylesheet());
    if (model.analysis.boundary_error)
      write_text(tmp / "boundary.html", absolute_links_html(boundary_html(model), options.link_base));
    write_text(tmp / "summary.md", summary_markdown(model, options.link_base));
    // The data files (--data), each written in parallel chunks.
    for (const DataFile& f : data_files(model.data)) {
      clock.start("write " + f.path.substr(f.path.find('/') + 1));
      const TextEncoding text = f.format == "csv.gz" ? TextEncoding::gzip : TextEncoding::plain;
      write_file(tmp / f.path, [&](std::ostream& out) {
        if (f.format == "vtu" || f.format == "vtu.zlib")
          write_annotated_vtu(model, out, model.data.vtu);
        else if (f.path.starts_with("data/cells."))
          write_cells_csv(model, out, text);
        else if (f.path.starts_with("data/vertices."))
          write_vertices_csv(model, out, text);
        else if (f.path == "data/non_conforming_faces.csv")
          write_non_conforming_faces_csv(model, out);
        else
          write_edges_csv(model, out);
      });
    }
    if (model.has_viewer) {
      clock.start("write viewer");
      fs::create_directories(tmp / "viewer");
      for (const ViewerFile& f : viewer_files(model)) write_text(tmp / f.relative_path, f.text);
    }
    clock.start("write images");
    for (const BundleImage& img : images) fs::create_directories((tmp / img.relative_path).parent_path());
    // PNG encoding dominates the writing of many views: one image per task.
    tbb::parallel_for(std::size_t{0}, images.size(), [&](std::size_t i) {
      const BundleImage& img = images[i];
      const fs::path path = tmp / img.relative_path;
      if (!img.text.empty())
        write_text(path, img.text);  // an SVG chart
      else
        write_text(path, encode_png(img.image));
    });
    if (options.single_file != SingleFile::none) {
      clock.start("write report.html");
      write_text(tmp / "report.html", single_file_of(tmp, options));
    }
    clock.stop();
    double wall = 0;
    for (const StageTime& t : timings) wall += t.concurrent ? 0.0 : t.seconds;
    if (options.started)
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - *options.started).count();
    write_text(tmp / "timings.json", timings_json(timings, wall));
    fault_point("bundle-before-swap");
    // The last poll point: a signal that comes later finds the bundle in
    // place (main then says that it arrived after the work was complete).
    stop::check();
    swap_into_place(tmp, dir);
  } catch (const fs::filesystem_error& e) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw EnvironmentError("writing the bundle: " + describe(e));
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
}

}  // namespace hq
