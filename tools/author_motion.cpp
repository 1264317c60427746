// Authors a motion of the project's figure from its keyframes: vdcloth_author_motion KEYS.json
// OUT.bvh. The shipped motions/*.bvh are made this way from motions/*.json.
#include <cstdio>
#include <exception>

#include "scene/bvh_motion.hpp"
#include "scene/figure.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: vdcloth_author_motion KEYS.json OUT.bvh\n");
    return 2;
  }
  try {
    const vdc::Motion m = vdc::author_motion_file(argv[1]);
    if (!vdc::write_bvh(m, argv[2])) {
      std::fprintf(stderr, "vdcloth_author_motion: %s: cannot write\n", argv[2]);
      return 2;
    }
    std::printf("%s: %zu frames, %.2f s\n", argv[2], m.frames.size(), m.duration());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vdcloth_author_motion: %s\n", e.what());
    return 2;
  }
}
