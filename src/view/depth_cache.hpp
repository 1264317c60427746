// Depth images that every garment group of a scene shares: what the scene's bodies hide from
// the camera at one of eq. 4's sample times (view.occlusion) is the same for every group, so
// it is drawn once, by the first group that asks, and each group adds its own garments to a
// copy. One cache serves one scene's cameras, each image kept under its camera's index.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "view/depth_image.hpp"

namespace vdc {

class DepthCache {
 public:
  // The image, not eroded, of `triangles()` seen by `camera` (the scene's camera number
  // `index`) at time t at `scale` times its size: drawn by the first caller for that camera and
  // time (triangles() called once), copied to each.
  DepthImage at(int index, double t, const Camera& camera, double scale, const std::function<std::vector<Triangle>()>& triangles);
  // Forgets the images of times before t.
  void forget_before(double t);
  std::size_t size() const;

 private:
  struct Entry {
    std::once_flag drawn;
    std::optional<DepthImage> image;
  };
  mutable std::mutex mutex_;
  std::map<std::pair<double, int>, std::shared_ptr<Entry>> entries_;  // by time, then camera
};

}  // namespace vdc
