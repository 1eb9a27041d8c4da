#include "scene/import_transform.h"

#include <cmath>
#include <string>
#include <vector>

#include "scene/suggest.h"

namespace pt {
namespace {

const std::vector<std::string> kSteps = {"translate", "rotate", "scale", "matrix"};

bool step_error(ReadContext& ctx, const JsonValue& v, const std::string& message) {
  ctx.diag.error(ctx.at(v), message);
  return false;
}

// Exactly n finite numbers (n == 1: a number, else an array of n).
bool numbers(ReadContext& ctx, const JsonValue& v, const std::string& label, std::size_t n, double* out) {
  const std::string expected = n == 1 ? "a number" : "an array of " + std::to_string(n) + " numbers";
  auto one = [&](const JsonValue& x, double& d) {
    if (!x.is_number() || !std::isfinite(x.as_number())) return false;
    d = x.as_number();
    return true;
  };
  if (n == 1) return one(v, out[0]) || step_error(ctx, v, "expected " + expected + " for '" + label + "'");
  if (!v.is_array() || v.as_array().size() != n) {
    return step_error(ctx, v, "expected " + expected + " for '" + label + "'");
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!one(v.as_array()[i], out[i])) {
      return step_error(ctx, v.as_array()[i], "expected a finite number in '" + label + "'");
    }
  }
  return true;
}

bool read_rotate(ReadContext& ctx, const JsonValue& v, Affine& out) {
  if (!expect_object(ctx, v, "rotate")) return false;
  ObjectReader r(ctx, v, "rotate");
  const JsonValue* axis = r.require("axis");
  const JsonValue* angle = r.require("angle");
  r.finish();
  double a[3], deg = 0;
  if (!axis || !angle || !r.ok() || !numbers(ctx, *axis, "axis", 3, a) || !numbers(ctx, *angle, "angle", 1, &deg)) {
    return false;
  }
  if (a[0] == 0 && a[1] == 0 && a[2] == 0) return step_error(ctx, *axis, "a rotation axis must not be zero");
  out = Affine::rotate(a[0], a[1], a[2], deg);
  return true;
}

bool read_scale(ReadContext& ctx, const JsonValue& v, Affine& out) {
  double s[3];
  if (v.is_number()) {
    if (!numbers(ctx, v, "scale", 1, s)) return false;
    s[1] = s[2] = s[0];
  } else if (!numbers(ctx, v, "scale", 3, s)) {
    return false;
  }
  out = Affine::scale(s[0], s[1], s[2]);
  return true;
}

// 16 numbers, row-major, acting on column vectors; the last row 0 0 0 1.
bool read_matrix(ReadContext& ctx, const JsonValue& v, Affine& out) {
  double m[16];
  if (!numbers(ctx, v, "matrix", 16, m)) return false;
  if (m[12] != 0 || m[13] != 0 || m[14] != 0 || m[15] != 1) {
    return step_error(ctx, v, "a transform matrix must be affine: its last row must be [0, 0, 0, 1] (row-major, "
                              "translation in the last column)");
  }
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) out.m[i][j] = m[4 * i + j];
  }
  return true;
}

bool read_step(ReadContext& ctx, const JsonValue& step, std::size_t index, Affine& out) {
  const std::string label = "transform[" + std::to_string(index) + "]";
  if (!step.is_object() || step.as_object().size() != 1) {
    return step_error(ctx, step, "expected an object with one key (" + quoted_list(kSteps, "or") + ") for '" +
                                     label + "'");
  }
  const JsonMember& m = step.as_object()[0];
  const JsonValue& v = m.value;
  if (m.key == "translate") {
    double t[3];
    if (!numbers(ctx, v, "translate", 3, t)) return false;
    out = Affine::translate(t[0], t[1], t[2]);
    return true;
  }
  if (m.key == "rotate") return read_rotate(ctx, v, out);
  if (m.key == "scale") return read_scale(ctx, v, out);
  if (m.key == "matrix") return read_matrix(ctx, v, out);
  std::string message = "unknown transform step '" + m.key + "'";
  message += did_you_mean(m.key, kSteps, "; the steps are " + quoted_list(kSteps, "and"));
  return step_error(ctx, step, message);
}

}  // namespace

bool read_transform(ReadContext& ctx, const JsonValue& v, std::optional<Sourced<Transform>>& out) {
  if (!expect_array(ctx, v, "transform")) return false;
  Affine total;
  const JsonValue::Array& steps = v.as_array();
  for (std::size_t i = 0; i < steps.size(); ++i) {
    Affine step;
    if (!read_step(ctx, steps[i], i, step)) return false;
    if (!step.invertible()) {
      return step_error(ctx, steps[i], "this transform step is singular (it flattens the object; a scale of 0 "
                                       "or a matrix without an inverse)");
    }
    total = step * total;  // later steps act after earlier ones
    if (!total.invertible()) {
      return step_error(ctx, steps[i], "the transform up to this step is singular or not finite");
    }
  }
  if (total.is_identity()) {
    out.reset();
    return true;
  }
  const Transform t(total);
  if (!t.finite()) return step_error(ctx, v, "this transform's matrix or its inverse is beyond float range");
  out = Sourced<Transform>(t, ctx.at(v));
  return true;
}

}  // namespace pt
