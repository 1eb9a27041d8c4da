#include "scene/legacy_common.h"

#include <vector>

#include "scene/suggest.h"

namespace pt {

bool read_corners(ObjectReader& r, int n, Sourced<Vec3f>* out) {
  bool ok = true;
  for (int i = 0; i < n; ++i) {
    const char key[3] = {'v', static_cast<char>('0' + i), '\0'};  // n <= 4
    ok = r.read_required(key, out[i]) && ok;
  }
  return ok;
}

std::string read_legacy_type(ObjectReader& r) {
  Sourced<std::string> type;
  if (!r.read_required("type", type)) return {};
  return type.value;
}

void warn_unsupported_type(ObjectReader& r, std::string_view kind, const std::string& type,
                           std::initializer_list<std::string_view> supported) {
  const std::vector<std::string> names(supported.begin(), supported.end());
  std::string message = "unsupported " + std::string(kind) + " type '" + type + "' (ignored)";
  const std::string suggestion = closest_match(type, names);
  if (!suggestion.empty()) message += "; did you mean '" + suggestion + "'?";
  else message += "; supported: " + quoted_list(names, "and");
  const JsonValue* v = r.get("type");
  r.context().diag.warning(v ? r.context().at(*v) : r.where(), std::move(message));
}

}  // namespace pt
