#include "experiments/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/atomic_write.h"
#include "core/error.h"
#include "core/image_io.h"
#include "experiments/scoring.h"

namespace dp::experiments {

namespace fs = std::filesystem;

namespace {

std::string num(double v, const char* fmt = "%.4g") {
  char buf[64];
  std::snprintf(buf, sizeof(buf), fmt, v);
  return buf;
}

// `width` > 0 sets the displayed width (small renders are shown enlarged, pixelated).
std::string img_tag(const std::string& src, const std::string& alt, const std::string& caption, int width = 0) {
  const std::string w = width > 0 ? " width=\"" + std::to_string(width) + "\"" : std::string();
  return "<figure><img src=\"" + html_escape(src) + "\" alt=\"" + html_escape(alt) + "\"" + w + "><figcaption>" +
         caption + "</figcaption></figure>\n";
}

// Outlines each crop on a copy of the image (2 px, alternating colours).
core::Image outline_crops(core::Image img, const std::vector<Crop>& crops) {
  static const Rgb kColours[3] = {Rgb(1.0f, 0.2f, 0.2f), Rgb(0.2f, 1.0f, 0.2f), Rgb(0.3f, 0.5f, 1.0f)};
  for (size_t i = 0; i < crops.size(); ++i) {
    const Crop& c = crops[i];
    const Rgb col = kColours[i % 3];
    for (int t = 0; t < 2; ++t) {
      const int x0 = std::max(c.x - 1 - t, 0), x1 = std::min(c.x + c.w + t, img.width() - 1);
      const int y0 = std::max(c.y - 1 - t, 0), y1 = std::min(c.y + c.h + t, img.height() - 1);
      for (int x = x0; x <= x1; ++x) img(x, y0) = img(x, y1) = col;
      for (int y = y0; y <= y1; ++y) img(x0, y) = img(x1, y) = col;
    }
  }
  return img;
}

const PointResult* find_point(const ExperimentResult& r, size_t run, size_t budget, int seed) {
  for (const auto& p : r.points)
    if (p.run == run && p.budget == budget && p.seed == seed) return &p;
  return nullptr;
}

core::Image read_layer(const PointResult& p) {
  for (auto& l : core::read_exr_layers(p.exr_path))
    if (l.name == p.layer) return std::move(l.image);
  throw IoError("layer '" + p.layer + "' missing", p.exr_path);
}

const char* kStyle = R"(
body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fafafa; }
h1 { font-size: 1.4em; } h2 { font-size: 1.15em; margin-top: 1.6em; border-bottom: 1px solid #ccc; }
figure { display: inline-block; margin: 0.4em; vertical-align: top; text-align: center; }
figure img { display: block; image-rendering: pixelated; border: 1px solid #999; max-width: 512px; }
figcaption { font-size: 0.85em; margin-top: 0.2em; }
table { border-collapse: collapse; font-size: 0.85em; }
td, th { border: 1px solid #bbb; padding: 0.15em 0.5em; text-align: right; }
th { background: #eee; } td.name { text-align: left; }
.legend { display: inline-block; width: 320px; height: 14px; border: 1px solid #999; vertical-align: middle; }
.plot img { max-width: 900px; border: none; }
)";

}  // namespace

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&#39;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string write_report(const ExperimentConfig& config, const ExperimentResult& result, const core::Image& reference) {
  const fs::path dir(config.output);
  const fs::path img_dir = dir / "report";
  fs::create_directories(img_dir);
  const size_t top = size_t(std::max_element(config.budgets.begin(), config.budgets.end()) - config.budgets.begin());
  const std::string top_text = config.budget_text(config.budgets[top]);

  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
                  html_escape(config.name) + " — Deltapath experiment</title>\n<style>" + kStyle + "</style>\n</head>\n<body>\n";
  h += "<h1>Experiment " + html_escape(config.name) + "</h1>\n<p>Scene <code>" + html_escape(config.scene) +
       "</code>; budgets " + std::string(config.budget_kind == BudgetKind::time ? "in wall-clock seconds" : "in samples per pixel") +
       "; " + std::to_string(config.seeds) + " seed(s) per point; reference <code>" + html_escape(result.reference_path) +
       "</code>" +
       (config.reference.file.empty()
            ? " (" + html_escape(config.reference.integrator) + ", " + std::to_string(config.reference.spp) + " spp)"
            : std::string()) +
       ". Experiment file <code>" + html_escape(config.file) + "</code>.</p>\n";

  // Convergence plot.
  h += "<h2>Convergence</h2>\n";
  if (!result.plot_png.empty()) {
    const std::string png = fs::path(result.plot_png).lexically_relative(dir).generic_string();
    const std::string svg = fs::path(result.plot_png).replace_extension(".svg").lexically_relative(dir).generic_string();
    h += "<div class=\"plot\">" +
         img_tag(png, "convergence plot",
                 "Error against wall-clock time (log-log), mean over seeds with min–max spread. <a href=\"" +
                     html_escape(svg) + "\">SVG</a>") +
         "</div>\n";
  } else {
    h += "<p>No plot (python3 with matplotlib was not available); the numbers are in the tables below.</p>\n";
  }

  // Summary: mean over seeds per (run, budget).
  h += "<h2>Summary (mean over seeds)</h2>\n<table>\n<tr><th>run</th><th>integrator</th><th>budget</th><th>wall time [s]</th><th>spp</th>";
  for (const auto& m : config.metrics) h += "<th>" + html_escape(m.column()) + "</th>";
  h += "</tr>\n";
  for (size_t r = 0; r < config.runs.size(); ++r)
    for (size_t b = 0; b < config.budgets.size(); ++b) {
      double t = 0, spp = 0;
      std::vector<double> mv(config.metrics.size(), 0.0);
      int n = 0;
      for (const auto& p : result.points) {
        if (p.run != r || p.budget != b) continue;
        t += p.wall_time;
        spp += double(p.spp);
        for (size_t m = 0; m < mv.size(); ++m) mv[m] += p.metrics[m];
        ++n;
      }
      if (n == 0) continue;
      h += "<tr><td class=\"name\">" + html_escape(config.runs[r].name) + "</td><td class=\"name\">" +
           html_escape(config.runs[r].integrator) + "</td><td>" + html_escape(config.budget_text(config.budgets[b])) +
           "</td><td>" + num(t / n) + "</td><td>" + num(spp / n, "%.1f") + "</td>";
      for (double v : mv) h += "<td>" + num(v / n) + "</td>";
      h += "</tr>\n";
    }
  h += "</table>\n";

  // Images at the largest budget.
  const int shown = std::clamp(reference.width(), 256, 512);
  core::write_png((img_dir / "reference.png").string(), reference);
  h += "<h2>Images at " + html_escape(top_text) + " (seed 0)</h2>\n";
  h += img_tag("report/reference.png", "reference", "reference", shown);
  std::vector<core::Image> run_images(config.runs.size());
  for (size_t r = 0; r < config.runs.size(); ++r) {
    const PointResult* p = find_point(result, r, top, 0);
    if (!p) continue;
    run_images[r] = read_layer(*p);
    const std::string slug = config.runs[r].slug;
    core::write_png((img_dir / (slug + ".png")).string(), run_images[r]);
    std::string caption = html_escape(config.runs[r].name) + " (" + std::to_string(p->spp) + " spp, " +
                          num(p->wall_time, "%.2f") + " s)";
    for (size_t m = 0; m < config.metrics.size(); ++m)
      caption += "<br>" + html_escape(config.metrics[m].column()) + " " + num(p->metrics[m]);
    h += img_tag("report/" + slug + ".png", config.runs[r].name, caption, shown);
  }

  // Error maps.
  h += "<h2>Per-pixel relative squared error at " + html_escape(top_text) + "</h2>\n<p>(X − R)² / (R² + 10<sup>−3</sup>), mean over channels; 10<sup>" +
       num(kErrorMapLog10Min, "%.0f") + "</sup> <span class=\"legend\" style=\"background: linear-gradient(to right";
  for (int i = 0; i <= 8; ++i) {
    const Rgb c = error_ramp(i / 8.0);
    char buf[32];
    std::snprintf(buf, sizeof(buf), ", #%02x%02x%02x", int(c[0] * 255.0f + 0.5f), int(c[1] * 255.0f + 0.5f),
                  int(c[2] * 255.0f + 0.5f));
    h += buf;
  }
  h += ");\"></span> 10<sup>" + num(kErrorMapLog10Max, "%.0f") + "</sup>; magenta = non-finite.</p>\n";
  for (size_t r = 0; r < config.runs.size(); ++r) {
    if (run_images[r].empty()) continue;
    const std::string name = config.runs[r].slug + "-error.png";
    core::write_png((img_dir / name).string(), error_map(run_images[r], reference));
    h += img_tag("report/" + name, config.runs[r].name + " error", html_escape(config.runs[r].name), shown);
  }

  // Crops.
  if (!config.crops.empty()) {
    core::write_png((img_dir / "reference-crops.png").string(), outline_crops(reference, config.crops));
    h += "<h2>Crops at " + html_escape(top_text) + "</h2>\n";
    h += img_tag("report/reference-crops.png", "crop locations", "crop locations (red, green, blue, ...)", shown);
    for (size_t k = 0; k < config.crops.size(); ++k) {
      const Crop& c = config.crops[k];
      h += "<div>\n";
      const std::string ref_name = "crop" + std::to_string(k) + "-reference.png";
      core::write_png((img_dir / ref_name).string(), crop_image(reference, c));
      h += img_tag("report/" + ref_name, "reference crop",
                   "reference [" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " + std::to_string(c.w) + ", " +
                       std::to_string(c.h) + "]");
      for (size_t r = 0; r < config.runs.size(); ++r) {
        if (run_images[r].empty()) continue;
        const std::string name = "crop" + std::to_string(k) + "-" + config.runs[r].slug + ".png";
        core::write_png((img_dir / name).string(), crop_image(run_images[r], c));
        h += img_tag("report/" + name, config.runs[r].name + " crop", html_escape(config.runs[r].name));
      }
      h += "</div>\n";
    }
  }

  // Every point.
  const std::string csv_rel = fs::path(result.csv_path).lexically_relative(dir).generic_string();
  h += "<h2>All points (<a href=\"" + html_escape(csv_rel) + "\">" + html_escape(csv_rel) +
       "</a>)</h2>\n<table>\n<tr><th>name</th><th>budget</th><th>seed</th><th>wall_time</th><th>spp</th>";
  for (const auto& m : config.metrics) h += "<th>" + html_escape(m.column()) + "</th>";
  h += "</tr>\n";
  for (const auto& p : result.points) {
    h += "<tr><td class=\"name\">" + html_escape(config.runs[p.run].name) + "</td><td>" + num(config.budgets[p.budget]) +
         "</td><td>" + std::to_string(p.seed) + "</td><td>" + num(p.wall_time) + "</td><td>" + std::to_string(p.spp) + "</td>";
    for (double v : p.metrics) h += "<td>" + num(v) + "</td>";
    h += "</tr>\n";
  }
  h += "</table>\n</body>\n</html>\n";

  const std::string path = (dir / "report.html").string();
  core::write_file_atomically(path, h);
  return path;
}

}  // namespace dp::experiments
