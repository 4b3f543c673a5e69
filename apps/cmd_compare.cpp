// `deltapath compare IMAGE REFERENCE [--json]`: MSE, relMSE (eps 1e-3, per channel),
// MAPE and the per-channel ratio of image means.
#include <cstdio>

#include "apps/commands.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/json.h"
#include "core/metrics.h"

namespace dp::apps {

namespace {
struct CompareArgs {
  std::string image, reference;
  bool json = false;
  size_t discard = 0;
};

void run_compare(const CompareArgs& a) {
  const core::Image x = core::read_image(a.image);
  const core::Image r = core::read_image(a.reference);
  if (!x.same_size(r))
    throw ValueError("image is " + std::to_string(x.width()) + "x" + std::to_string(x.height()) + " but the reference is " +
                         std::to_string(r.width()) + "x" + std::to_string(r.height()),
                     a.image);
  const core::ErrorReport e = core::compare(x, r, a.discard);
  if (a.json) {
    core::Json j = core::Json::object();
    j["image"] = a.image;
    j["reference"] = a.reference;
    j["mse"] = e.mse;
    j["relmse"] = e.relmse;
    j["mape"] = e.mape;
    j["mean_ratio"] = core::Json(core::Json::Array{e.mean_ratio[0], e.mean_ratio[1], e.mean_ratio[2]});
    j["nonfinite_pixels"] = uint64_t(e.nonfinite);
    std::printf("%s", j.dump().c_str());
    return;
  }
  std::printf("MSE:        %.6g\n", e.mse);
  std::printf("relMSE:     %.6g\n", e.relmse);
  std::printf("MAPE:       %.6g\n", e.mape);
  std::printf("mean ratio: R %.5f  G %.5f  B %.5f\n", e.mean_ratio[0], e.mean_ratio[1], e.mean_ratio[2]);
  std::printf("means:      image (%.5g %.5g %.5g)  reference (%.5g %.5g %.5g)\n", e.mean_image[0], e.mean_image[1],
              e.mean_image[2], e.mean_reference[0], e.mean_reference[1], e.mean_reference[2]);
  if (e.nonfinite) std::printf("non-finite pixels in image: %zu (excluded)\n", e.nonfinite);
}
}  // namespace

void register_compare(CLI::App& app) {
  auto args = std::make_shared<CompareArgs>();
  CLI::App* cmd = app.add_subcommand("compare", "error metrics of an image against a reference");
  cmd->add_option("image", args->image, "image (EXR, PNG, JPEG)")->required();
  cmd->add_option("reference", args->reference, "reference image")->required();
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->add_option("--discard", args->discard, "drop the n pixels with the largest error");
  cmd->callback([args] { run_compare(*args); });
}

}  // namespace dp::apps
