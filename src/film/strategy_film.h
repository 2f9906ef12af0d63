// Per-strategy images for the bidirectional tracer (`--strategies DIR`), as
// pbrt's visualizestrategies: for each (s, t), and for each merge (s, t)
// of vcm, one image of its weighted contributions (they sum to the image)
// and one unweighted (each is an estimator of all paths that strategy can
// sample). A debugging aid: memory grows with the number of strategies
// times the image size.
#pragma once

#include <vector>

#include "film/film.h"
#include "lantern/render.h"

namespace lantern {

class StrategyFilm {
 public:
  StrategyFilm(int width, int height, const PixelFilter& filter) : width_(width), height_(height), filter_(filter) {}
  // Serially, in wave order, like Film::merge, through the film's sensor.
  void merge(const std::vector<StrategyRecord>& records, const Film& film);
  // Normalised as the main film is: camera-side strategies by each pixel's
  // sample count, light tracing by the light-subpath count.
  std::vector<StrategyImage> resolve(const Film& film) const;

 private:
  struct Sums {
    int s = -1, t = -1;
    bool merge = false;
    std::vector<double> weighted, unweighted;
  };
  Sums& sums(int s, int t, bool merge);

  int width_, height_;
  PixelFilter filter_;
  std::vector<Sums> strategies_;
};

}  // namespace lantern
