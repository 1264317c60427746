// Depth images shared by a scene's garment groups (occlusion, an extension of Koh et al. 2014,
// sec. 3.1).
#include "view/depth_cache.hpp"

#include <limits>

namespace vdc {

DepthImage DepthCache::at(int index, double t, const Camera& camera, double scale, const std::function<std::vector<Triangle>()>& triangles) {
  std::shared_ptr<Entry> entry;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = entries_[{t, index}];
    if (!slot) slot = std::make_shared<Entry>();
    entry = slot;
  }
  // Drawn outside the lock: groups asking for other times are not held up.
  std::call_once(entry->drawn, [&] {
    DepthImage image(camera, scale);
    image.draw(triangles());
    entry->image.emplace(std::move(image));
  });
  return *entry->image;
}

void DepthCache::forget_before(double t) {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.erase(entries_.begin(), entries_.lower_bound({t, std::numeric_limits<int>::min()}));
}

std::size_t DepthCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

}  // namespace vdc
