#include "hqview/report/bundle_writer.h"

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

#include <tbb/parallel_for.h>

#include <nlohmann/json.hpp>

#include "hqview/core/error.h"
#include "hqview/image/png.h"
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
  if (!out) throw Error(path.string() + ": cannot create: " + std::strerror(errno));
  write(out);
  out.flush();
  if (!out) throw Error(path.string() + ": write failed: " + std::strerror(errno));
}

void write_text(const fs::path& path, std::string_view text) {
  write_file(path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

fs::path sibling(const fs::path& dir, const char* tag) {
  // Built with += : GCC 12 warns falsely (-Wrestrict) on chained operator+.
  std::string name = ".";
  name += dir.filename().string();
  name += '.';
  name += tag;
  name += '-';
  name += std::to_string(::getpid());
  return dir.parent_path() / name;
}

}  // namespace

std::string timings_json(const std::vector<StageTime>& timings, double wall_seconds) {
  nlohmann::json stages = nlohmann::json::array();
  double total = 0.0;
  for (const StageTime& t : timings) {
    stages.push_back(
        {{"name", t.name}, {"seconds", t.seconds}, {"peak_rss_mb", std::round(t.peak_rss_bytes / 1e5) / 10}});
    total += t.seconds;
  }
  const nlohmann::json j = {
      {"note", "wall seconds of this run's stages; differs from run to run (report.json does not)"},
      {"stages", std::move(stages)},
      {"total_seconds", total},
      {"wall_seconds", wall_seconds}};
  return j.dump(2) + "\n";
}

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
  fs::create_directories(dir.parent_path());
  const fs::path tmp = sibling(dir, "hqview-tmp");
  fs::remove_all(tmp);
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
    write_text(tmp / "index.html", index_html(model));
    write_text(tmp / "style.css", report_stylesheet());
    if (model.analysis.boundary_error) write_text(tmp / "boundary.html", boundary_html(model));
    write_text(tmp / "summary.md", summary_markdown(model));
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
    clock.stop();
    double wall = 0;
    for (const StageTime& t : timings) wall += t.seconds;
    if (options.started)
      wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - *options.started).count();
    write_text(tmp / "timings.json", timings_json(timings, wall));
    // Swap into place: the old bundle is moved aside, never deleted before
    // the new one is in place.
    if (fs::exists(dir)) {
      const fs::path old = sibling(dir, "hqview-old");
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
  } catch (const fs::filesystem_error& e) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw Error(std::string("writing the bundle: ") + e.what());
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(tmp, ignored);
    throw;
  }
}

}  // namespace hq
