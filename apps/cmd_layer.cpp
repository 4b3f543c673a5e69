// `deltapath layer IN.exr NAME --out OUT.(exr|png) [--exposure E] [--abs]`: one layer of a
// multi-layer render as its own image (a gradient layer, the density, features, AO, ...).
// PNG: sRGB preview of the values times the exposure scale (--abs: of their magnitudes,
// for signed layers such as dx, dy and pairs.<k>).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_io.h"

namespace dp::apps {

namespace {
struct LayerArgs {
  std::string in, name, out;
  float exposure = 1.0f;
  bool abs = false;
};

void run_layer(const LayerArgs& a) {
  std::vector<core::NamedLayer> layers = core::read_exr_layers(a.in);
  std::string names;
  for (auto& l : layers) {
    if (l.name == a.name || (a.name == "RGB" && l.name.empty())) {
      core::Image img = std::move(l.image);
      if (a.abs)
        for (Rgb& p : img.pixels()) p = p.abs();
      const std::string ext = std::filesystem::path(a.out).extension().string();
      if (ext == ".exr")
        core::write_exr(a.out, img);
      else if (ext == ".png")
        core::write_png(a.out, img, a.exposure);
      else
        throw ValueError("layer: --out must end in .exr or .png", a.out);
      std::printf("layer: wrote '%s' of %s (%dx%d) to %s\n", a.name.c_str(), a.in.c_str(), img.width(), img.height(),
                  a.out.c_str());
      return;
    }
    names += (names.empty() ? "" : ", ") + (l.name.empty() ? std::string("RGB") : l.name);
  }
  throw ValueError("no layer '" + a.name + "' (layers: " + names + ")", a.in);
}
}  // namespace

void register_layer(CLI::App& app) {
  auto args = std::make_shared<LayerArgs>();
  CLI::App* cmd = app.add_subcommand("layer", "write one layer of a multi-layer EXR as an EXR or PNG image");
  cmd->add_option("in", args->in, "multi-layer EXR (a render)")->required();
  cmd->add_option("name", args->name, "layer name (RGB = the main image)")->required();
  cmd->add_option("--out", args->out, "output .exr or .png")->required();
  cmd->add_option("--exposure", args->exposure, "PNG only: scale applied before the sRGB preview (default 1)");
  cmd->add_flag("--abs", args->abs, "magnitudes of the values (signed layers)");
  cmd->callback([args] { run_layer(*args); });
}

}  // namespace dp::apps
