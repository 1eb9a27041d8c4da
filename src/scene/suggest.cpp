#include "scene/suggest.h"

#include <algorithm>
#include <cctype>

namespace pt {

int edit_distance(std::string_view a, std::string_view b) {
  const std::size_t n = a.size(), m = b.size();
  // Three rows suffice for the transposition step.
  std::vector<int> prev2(m + 1), prev(m + 1), cur(m + 1);
  for (std::size_t j = 0; j <= m; ++j) prev[j] = static_cast<int>(j);
  for (std::size_t i = 1; i <= n; ++i) {
    cur[0] = static_cast<int>(i);
    for (std::size_t j = 1; j <= m; ++j) {
      const int cost = a[i - 1] == b[j - 1] ? 0 : 1;
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        cur[j] = std::min(cur[j], prev2[j - 2] + 1);
    }
    std::swap(prev2, prev);
    std::swap(prev, cur);
  }
  return prev[m];
}

namespace {
std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return r;
}
}  // namespace

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  const std::string w = lower(word);
  std::string best;
  int best_distance = 0;
  for (const std::string& c : candidates) {
    const int d = edit_distance(w, lower(c));
    if (best.empty() || d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  // Words of 1-2 characters: only case differences ("kt" is not a typo of
  // "ks"); then one edit, two for 6+ characters, three for 12+.
  const int len = static_cast<int>(word.size());
  const int allowed = len <= 2 ? 0 : (len < 6 ? 1 : (len < 12 ? 2 : 3));
  if (best.empty() || best_distance > allowed) return {};
  // In a short key the first letter names what it is about ("tPath" a texture,
  // "mPath" a mesh; "uv0" a texture coordinate, "v0" a corner): another first
  // letter is another key, not a typo.
  if (len < 6 && best_distance > 0 && w[0] != lower(best)[0]) return {};
  return best;
}

std::string quoted(std::string_view word) {
  std::string out;
  out.reserve(word.size() + 2);
  out.push_back('\'');
  out.append(word);
  out.push_back('\'');
  return out;
}

std::string did_you_mean(std::string_view word, const std::vector<std::string>& candidates, std::string otherwise) {
  const std::string suggestion = closest_match(word, candidates);
  return suggestion.empty() ? otherwise : "; did you mean '" + suggestion + "'?";
}

std::string quoted_list(std::vector<std::string> items, std::string_view conjunction) {
  std::sort(items.begin(), items.end());
  items.erase(std::unique(items.begin(), items.end()), items.end());
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) {
      if (i + 1 == items.size()) out.append(" ").append(conjunction).append(" ");
      else out.append(", ");
    }
    out += quoted(items[i]);
  }
  return out;
}

}  // namespace pt
