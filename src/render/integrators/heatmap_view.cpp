// Debug view "bvh-cost": how much work the acceleration structure does for
// each pixel's camera ray(s) - nodes visited plus primitives tested, averaged
// over the pixel's samples - as a heat map on the viridis ramp (perceptually
// uniform, dark = cheap, yellow = expensive). The ramp spans 0 to the 99th
// percentile of the image's costs (the few costlier pixels saturate, so that
// the rest of the image keeps its contrast). A legend is drawn into the
// bottom-left corner: the colour bar with 0 under its left end and the top of
// the scale under its right end, followed by "+" when some pixels saturate.
// It is how a user sees why a scene is slow. Needs a backend that counts its
// traversal work (--accel=bvh); can_render() says so before anything renders.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/srgb.h"
#include "render/film/film.h"
#include "render/integrators/builtin.h"
#include "render/integrators/render_loop.h"
#include "render/render_scene.h"

namespace pt {

namespace {

// Viridis (van der Walt and Smith; matplotlib's 256-entry table, CC0), every
// 16th entry and the last, sRGB-encoded.
constexpr std::array<std::array<float, 3>, 17> kViridis{{
    {0.267004f, 0.004874f, 0.329415f}, {0.282327f, 0.094955f, 0.417331f}, {0.278826f, 0.175490f, 0.483397f},
    {0.258965f, 0.251537f, 0.524736f}, {0.229739f, 0.322361f, 0.545706f}, {0.199430f, 0.387607f, 0.554642f},
    {0.172719f, 0.448791f, 0.557885f}, {0.149039f, 0.508051f, 0.557250f}, {0.127568f, 0.566949f, 0.550556f},
    {0.120638f, 0.625828f, 0.533488f}, {0.157851f, 0.683765f, 0.501686f}, {0.246070f, 0.738910f, 0.452024f},
    {0.369214f, 0.788888f, 0.382914f}, {0.515992f, 0.831158f, 0.294279f}, {0.678489f, 0.863742f, 0.189503f},
    {0.845561f, 0.887322f, 0.099702f}, {0.993248f, 0.906157f, 0.143936f},
}};

// 3x5 glyphs for '0'..'9' and '+', row-major from the top, bit 14 = top-left.
constexpr std::array<uint16_t, 11> kGlyphs{{0x7B6F, 0x2C97, 0x73E7, 0x73CF, 0x5BC9, 0x79CF, 0x79EF, 0x7249, 0x7BEF,
                                            0x7BCF, 0x05D0}};

void fill(Image& image, int x0, int y0, int w, int h, RGB c) {
  for (int y = std::max(0, y0); y < std::min(image.height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(image.width, x0 + w); ++x) image.at(x, y) = c;
}

// Draws `text` (digits and '+') with its top-left corner at (x, y), `scale`
// pixels per glyph dot.
void draw_text(Image& image, const std::string& text, int x, int y, int scale, RGB c) {
  for (const char ch : text) {
    const bool digit = ch >= '0' && ch <= '9';
    if (!digit && ch != '+') continue;
    const uint16_t glyph = kGlyphs[digit ? static_cast<std::size_t>(ch - '0') : 10];
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (glyph & (1u << (14 - (row * 3 + col)))) fill(image, x + col * scale, y + row * scale, scale, scale, c);
    x += 4 * scale;
  }
}

int text_width(const std::string& text, int scale) { return static_cast<int>(text.size()) * 4 * scale - scale; }

// The legend: on a dark panel in the bottom-left corner, the colour bar (cost
// 0 on the left, `top` on the right, "+" if some pixels cost more) and the
// two numbers under its ends.
void draw_legend(Image& image, float top, bool saturated) {
  const int scale = std::max(1, image.height / 160);
  const int margin = 2 * scale;
  const int bar_w = std::max(8, image.width / 3);
  const int bar_h = std::max(3, 3 * scale);
  const std::string lo = "0", hi = std::to_string(static_cast<long long>(std::lround(top))) + (saturated ? "+" : "");
  const int panel_w = std::max(bar_w, text_width(lo, scale) + text_width(hi, scale) + 4 * scale) + 2 * margin;
  const int panel_h = bar_h + 5 * scale + 3 * margin;
  const int px = 0, py = image.height - panel_h;
  fill(image, px, py, panel_w, panel_h, RGB(0.0f));
  for (int i = 0; i < bar_w; ++i) {
    const RGB c = cost_colour(bar_w > 1 ? static_cast<float>(i) / static_cast<float>(bar_w - 1) : 0.0f);
    fill(image, px + margin + i, py + margin, 1, bar_h, c);
  }
  const int text_y = py + 2 * margin + bar_h;
  draw_text(image, lo, px + margin, text_y, scale, RGB(1.0f));
  draw_text(image, hi, px + margin + std::max(0, bar_w - text_width(hi, scale)), text_y, scale, RGB(1.0f));
}

class BvhCostIntegrator final : public Integrator {
 public:
  // A chart of every ray's cost: a miss costs too, whatever the film's transparency.
  explicit BvhCostIntegrator(const IntegratorSettings& settings) : settings_(settings) {
    settings_.film_transparent = false;
  }

  bool can_render(const RenderScene& scene, std::string& why) const override {
    if (scene.accel != nullptr && scene.accel->counts_traversal()) return true;
    why = "the bvh-cost view shows the work of our own BVH, which Embree does not report: use --accel=bvh";
    return false;
  }

  void render(const RenderScene& scene, Film& film, WorkerPool& pool) const override {
    if (!scene.accel->counts_traversal()) return;  // can_render() said why
    // Pass 1: the cost of each pixel (averaged over its samples).
    Film costs(film.width(), film.height());
    render_pixels(scene, costs, pool, settings_, [&](const Ray& ray) {
      Hit hit;
      TraversalCounters counters;
      const bool found = scene.accel->intersect_counted(ray, hit, counters);
      return CameraEstimate{RGB(static_cast<float>(counters.nodes + counters.primitives)), found};
    });
    // Pass 2: colours on the scale 0 .. 99th percentile, and the legend.
    std::vector<float> sorted;
    sorted.reserve(static_cast<std::size_t>(film.width()) * static_cast<std::size_t>(film.height()));
    for (int y = 0; y < film.height(); ++y)
      for (int x = 0; x < film.width(); ++x) sorted.push_back(costs.pixel(x, y).r);
    const auto p99 = sorted.begin() + static_cast<std::ptrdiff_t>((sorted.size() - 1) * 99 / 100);
    std::nth_element(sorted.begin(), p99, sorted.end());
    const float top = std::max(*p99, 1.0f);
    const bool saturated = *std::max_element(sorted.begin(), sorted.end()) > top;
    Image image(film.width(), film.height());
    for (int y = 0; y < film.height(); ++y)
      for (int x = 0; x < film.width(); ++x) image.at(x, y) = cost_colour(costs.pixel(x, y).r / top);
    draw_legend(image, top, saturated);
    // Only the film's crop is kept; the scale is the whole frame's, so a crop
    // shows the same colours as a full render.
    const PixelRect& crop = film.crop();
    for (int y = crop.y0; y < crop.y1; ++y) {
      for (int x = crop.x0; x < crop.x1; ++x) {
        PixelSum s;
        s.add(image.at(x, y), 1.0f, true);  // a chart: opaque everywhere
        film.add(x, y, s);
      }
    }
  }

 private:
  IntegratorSettings settings_;
};

}  // namespace

RGB cost_colour(float fraction) {
  const float f = std::clamp(std::isfinite(fraction) ? fraction : 0.0f, 0.0f, 1.0f) * (kViridis.size() - 1);
  const auto i = std::min(static_cast<std::size_t>(f), kViridis.size() - 2);
  const float w = f - static_cast<float>(i);
  RGB c;
  float* out[3] = {&c.r, &c.g, &c.b};
  for (int k = 0; k < 3; ++k) *out[k] = srgb_to_linear((1.0f - w) * kViridis[i][k] + w * kViridis[i + 1][k]);
  return c;
}

std::unique_ptr<Integrator> make_bvh_cost_integrator(const IntegratorSettings& settings) {
  return std::make_unique<BvhCostIntegrator>(settings);
}

}  // namespace pt
