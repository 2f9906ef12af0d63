// Levenshtein distance between two words (insertions, deletions and
// substitutions of one character each), and the nearest of a list: what a
// message needs to ask "did you mean ...?".
#pragma once

#include <algorithm>
#include <string>
#include <vector>

namespace lantern {

inline size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The first of `candidates` nearest to `word`, if within max_distance
// (and not `word` itself); "" otherwise.
inline std::string nearest_word(const std::string& word, const std::vector<std::string>& candidates,
                                size_t max_distance) {
  std::string best;
  size_t best_distance = max_distance + 1;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d > 0 && d < best_distance) best = c, best_distance = d;
  }
  return best;
}

}  // namespace lantern
