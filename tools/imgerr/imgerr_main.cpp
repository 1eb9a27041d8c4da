// pt-imgerr TEST REFERENCE [--rect X,Y,W,H] [--json]
//
// Prints the error of TEST against REFERENCE (any format OpenImageIO reads;
// EXR values as stored, 8-bit files as code / 255): MSE (linear RGB clamped to
// [0,1], channels summed, averaged over pixels), RMSE and relative MSE, as
// defined in docs/samplers.md. Exit status 0 on success, 1 on bad input
// (unreadable file, size mismatch, bad rectangle), 2 on bad arguments.
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/image_error.h"
#include "io/image_io.h"

int main(int argc, char** argv) {
  CLI::App app{"pt-imgerr: error of a test image against a reference (MSE, RMSE, relMSE)"};
  std::string test_path, reference_path, rect_text;
  bool json = false;
  app.add_option("test", test_path, "Test image")->required();
  app.add_option("reference", reference_path, "Reference image")->required();
  app.add_option("--rect", rect_text, "Compare only the rectangle X,Y,W,H (pixels, y down from the top)");
  app.add_flag("--json", json, "Print a JSON object instead of text");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  std::optional<pt::ImageRect> rect;
  if (!rect_text.empty()) {
    pt::ImageRect r;
    if (!pt::parse_image_rect(rect_text, r)) {
      std::cerr << "error: --rect " << rect_text << ": expected X,Y,W,H (integers, W and H > 0)\n";
      return 2;
    }
    rect = r;
  }
  pt::Image test, reference;
  std::string error;
  if (!pt::read_image(test_path, test, error)) {
    std::cerr << "error: " << test_path << ": " << error << "\n";
    return 1;
  }
  if (!pt::read_image(reference_path, reference, error)) {
    std::cerr << "error: " << reference_path << ": " << error << "\n";
    return 1;
  }
  pt::ImageError e;
  if (!pt::compute_image_error(test, reference, rect, e, error)) {
    std::cerr << "error: " << test_path << " vs " << reference_path << ": " << error << "\n";
    return 1;
  }
  if (json) {
    nlohmann::json j = {{"test", test_path}, {"reference", reference_path}, {"pixels", e.pixels},
                        {"mse", e.mse},       {"rmse", e.rmse},               {"rel_mse", e.rel_mse}};
    if (rect) j["rect"] = {rect->x, rect->y, rect->width, rect->height};
    std::cout << j.dump(2) << "\n";
  } else {
    std::printf("pixels  %lld\nmse     %.9g\nrmse    %.9g\nrel_mse %.9g\n", static_cast<long long>(e.pixels), e.mse,
                e.rmse, e.rel_mse);
  }
  return 0;
}
