// Crowds: copies of a template character and its dress placed on a grid, a circle or at seeded
// random positions (against hand computation), varied in start, speed and motion, each its own
// garment group; errors name the template's place and the copy.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/scene_crowds.hpp"
#include "scene/scene.hpp"

namespace vdc {
namespace {

namespace fs = std::filesystem;

std::vector<CrowdCopy> copies_of(const std::string& crowd) { return place_crowd(JsonValue(nlohmann::json::parse(crowd), "scene.json", "crowds[0]")); }

void expect_at(const Vec3& a, const Vec3& b) { EXPECT_LT((a - b).norm(), 1e-12) << a.transpose() << " vs " << b.transpose(); }

// Five on a grid of three columns, 2 m apart across and 3 m deep, centred on (1, 0, -1): two
// rows, x = 1 + (column - 1) 2, z = -1 + (row - 0.5) 3.
TEST(Crowd, AGridIsCentredRowByRow) {
  const auto c = copies_of(R"({"name": "d", "count": 5, "layout": {"grid": {"columns": 3, "spacing": [2, 3]}}, "centre": [1, 0, -1], "template": {}})");
  ASSERT_EQ(c.size(), 5u);
  expect_at(c[0].position, Vec3(-1, 0, -2.5));
  expect_at(c[1].position, Vec3(1, 0, -2.5));
  expect_at(c[2].position, Vec3(3, 0, -2.5));
  expect_at(c[3].position, Vec3(-1, 0, 0.5));
  expect_at(c[4].position, Vec3(1, 0, 0.5));
  EXPECT_EQ(c[0].group, "d01");
  EXPECT_EQ(c[4].group, "d05");
  for (const auto& copy : c) {
    EXPECT_EQ(copy.heading, 0.0);
    EXPECT_EQ(copy.start, 0.0);
    EXPECT_EQ(copy.speed, 1.0);
    EXPECT_EQ(copy.motion, "");
  }
  // Twelve default to ceil(sqrt(12)) = 4 columns 2 m apart: three rows.
  const auto twelve = copies_of(R"({"name": "p", "count": 12, "layout": {"grid": {}}, "template": {}})");
  expect_at(twelve[0].position, Vec3(-3, 0, -2));
  expect_at(twelve[11].position, Vec3(3, 0, 2));
  EXPECT_EQ(copies_of(R"({"name": "p", "count": 120, "layout": {"grid": {}}, "template": {}})")[119].group, "p120");
}

// Four on a circle of 2 m, each turned to face its centre (the figure faces +z at heading 0).
TEST(Crowd, ACircleFacingItsCentre) {
  const auto c = copies_of(R"({"name": "c", "count": 4, "layout": {"circle": {"radius": 2}}, "heading": "centre", "template": {}})");
  expect_at(c[0].position, Vec3(0, 0, 2));
  expect_at(c[1].position, Vec3(2, 0, 0));
  expect_at(Vec3(c[2].position.x(), 0, c[2].position.z()), Vec3(0, 0, -2));
  expect_at(c[3].position, Vec3(-2, 0, 0));
  EXPECT_NEAR(std::abs(c[0].heading), 180, 1e-9);
  EXPECT_NEAR(c[1].heading, -90, 1e-9);
  EXPECT_NEAR(c[3].heading, 90, 1e-9);
}

// Seeded random positions: in the area, apart, the same for the same seed; ranges drawn within
// their bounds; motions cycled or drawn.
TEST(Crowd, RandomPlacesAndVariationsComeFromTheSeed) {
  const std::string crowd = R"({"name": "r", "count": 30, "layout": {"random": {"size": [10, 6], "min_distance": 1}}, "centre": [5, 0, 0],
    "start": [0, 2], "speed": [0.8, 1.25], "heading": [-30, 30], "motions": ["a.bvh", "b.bvh"], "template": {}, "seed": 7})";
  const auto c = copies_of(crowd);
  ASSERT_EQ(c.size(), 30u);
  double start_spread = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    EXPECT_GE(c[k].position.x(), 0);
    EXPECT_LE(c[k].position.x(), 10);
    EXPECT_LE(std::abs(c[k].position.z()), 3);
    for (std::size_t m = 0; m < k; ++m) EXPECT_GE((c[k].position - c[m].position).norm(), 1.0);
    EXPECT_GE(c[k].start, 0);
    EXPECT_LE(c[k].start, 2);
    EXPECT_GE(c[k].speed, 0.8);
    EXPECT_LE(c[k].speed, 1.25);
    EXPECT_LE(std::abs(c[k].heading), 30);
    EXPECT_EQ(c[k].motion, k % 2 == 0 ? "a.bvh" : "b.bvh");
    start_spread = std::max(start_spread, std::abs(c[k].start - c[0].start));
  }
  EXPECT_GT(start_spread, 0.5);
  const auto again = copies_of(crowd);
  for (std::size_t k = 0; k < c.size(); ++k) {
    EXPECT_EQ(again[k].position, c[k].position);
    EXPECT_EQ(again[k].start, c[k].start);
  }
  std::string other = crowd;
  other.replace(other.find("\"seed\": 7"), 9, "\"seed\": 8");
  EXPECT_NE(copies_of(other)[0].position, c[0].position);
  std::string drawn = crowd;
  drawn.replace(drawn.find("\"template\""), 10, R"("motion_order": "random", "template")");
  int a = 0;
  for (const auto& copy : copies_of(drawn)) a += copy.motion == "a.bvh";
  EXPECT_GT(a, 5);
  EXPECT_LT(a, 25);
  // Fifty dancers a metre apart do not fit on 2 m by 2 m: the layout says so.
  try {
    copies_of(R"({"name": "r", "count": 50, "layout": {"random": {"size": [2, 2]}}, "template": {}})");
    ADD_FAILURE() << "placed fifty on 4 square metres";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crowds[0].layout.random"), std::string::npos) << e.what();
  }
}

// The mirror image of the dance: every joint where its partner (Left for Right) was, reflected
// in x = 0, at every frame looked at; mirrored twice, the dance itself.
TEST(Crowd, AMirroredMotionMovesEachJointAsItsPartnerReflected) {
  const Motion dance = read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh");
  const Motion mirror = mirrored(dance);
  const auto& joints = dance.skeleton.joints;
  auto index = [&](const std::string& name) {
    for (std::size_t j = 0; j < joints.size(); ++j)
      if (joints[j].name == name) return j;
    ADD_FAILURE() << "no joint " << name;
    return std::size_t{0};
  };
  int sided = 0;
  for (std::size_t f : {std::size_t{0}, dance.frames.size() / 3, dance.frames.size() - 1}) {
    const auto before = dance.world(dance.frame_pose(f)), after = mirror.world(mirror.frame_pose(f));
    for (std::size_t j = 0; j < joints.size(); ++j) {
      std::string partner = joints[j].name;
      if (partner.find("Left") != std::string::npos) partner.replace(partner.find("Left"), 4, "Right");
      else if (partner.find("Right") != std::string::npos) partner.replace(partner.find("Right"), 5, "Left");
      sided += partner != joints[j].name;
      const Vec3 p = before[index(partner)].translation();
      EXPECT_LT((after[j].translation() - Vec3(-p.x(), p.y(), p.z())).norm(), 1e-9) << joints[j].name << " frame " << f;
    }
  }
  EXPECT_GT(sided, 20);
  const Motion twice = mirrored(mirror);
  EXPECT_EQ(twice.frames, dance.frames);
  for (std::size_t j = 0; j < joints.size(); ++j) EXPECT_EQ(twice.skeleton.joints[j].offset, joints[j].offset);
  // The partners are found by the figure's shape: a name changes nothing, a hand holding a prop
  // the other does not hold has no mirror image.
  Motion renamed = dance;
  renamed.skeleton.joints[index("RightArm")].name = "RightWing";
  EXPECT_EQ(mirrored(renamed).frames, mirror.frames);
  Motion one_sided = dance;
  Joint prop;
  prop.name = "Sword";
  prop.parent = static_cast<int>(index("RightHand"));
  prop.offset = Vec3(-0.1, 0, 0);
  prop.first_channel = one_sided.skeleton.num_channels;
  one_sided.skeleton.joints.push_back(prop);
  try {
    mirrored(one_sided);
    ADD_FAILURE() << "mirrored a figure with a sword in its right hand and none in its left";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("joints 'LeftHand' and 'RightHand', one the other's mirror image, have 1 and 2 joints below them"),
              std::string::npos)
        << e.what();
  }
  // A crowd mirrors every other copy, every copy, or copies drawn from its seed.
  const auto alternate = copies_of(R"({"name": "m", "count": 4, "layout": {"grid": {}}, "mirror": "alternate", "template": {}})");
  EXPECT_FALSE(alternate[0].mirror);
  EXPECT_TRUE(alternate[1].mirror);
  EXPECT_FALSE(alternate[2].mirror);
  EXPECT_TRUE(alternate[3].mirror);
  for (const auto& c : copies_of(R"({"name": "m", "count": 3, "layout": {"grid": {}}, "mirror": true, "template": {}})")) EXPECT_TRUE(c.mirror);
  int drawn = 0;
  for (const auto& c : copies_of(R"({"name": "m", "count": 40, "layout": {"grid": {}}, "mirror": "random", "template": {}})")) drawn += c.mirror;
  EXPECT_GT(drawn, 10);
  EXPECT_LT(drawn, 30);
}

fs::path write_crowd_scene(const std::string& name, const std::string& crowd) {
  const fs::path dir = fs::temp_directory_path() / ("vdcloth-crowd-" + name + "-" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"frames": 2, "crowds": [)" << crowd << "]}";
  return dir / "scene.json";
}

// A crowd of three dancers in dresses: each copy is a character and a dress of its own group,
// the character and its dress standing where the layout put them, its clip started at the
// template's start plus the copy's offset.
TEST(Crowd, CopiesAreGarmentsAndCharactersOfTheirOwnGroups) {
  const std::string dir = VDCLOTH_SOURCE_DIR;
  const fs::path path = write_crowd_scene("three", R"({"name": "dancer", "count": 3, "layout": {"grid": {"columns": 3, "spacing": 3}},
    "start": [0, 1], "template": {"character": {"motion": ")" + dir + R"(/motions/dance.bvh", "start": 0.5, "resolution": 0.05},
    "garments": [{"name": "dress", "mesh": {"dress": {}}, "material": ")" + dir + R"(/materials/cotton.json"}]}})");
  const Scene s = load_scene(path.string());
  fs::remove_all(path.parent_path());
  ASSERT_EQ(s.garments.size(), 3u);
  ASSERT_EQ(s.obstacles.size(), 3u);
  const auto copies = copies_of(R"({"name": "dancer", "count": 3, "layout": {"grid": {"columns": 3, "spacing": 3}}, "start": [0, 1], "template": {}})");
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(s.garments[k].name, "dress_dancer0" + std::to_string(k + 1));
    EXPECT_EQ(s.garments[k].group, copies[k].group);
    EXPECT_EQ(s.obstacles[k].name, copies[k].group);
    EXPECT_EQ(s.obstacles[k].group, copies[k].group);
    ASSERT_TRUE(s.obstacles[k].character);
    EXPECT_DOUBLE_EQ(s.obstacles[k].character->start(), 0.5 + copies[k].start);
    // The body stands at its copy's place (its mean within the figure's own offset of it).
    Vec3 mean = Vec3::Zero();
    const std::vector<Vec3> x = s.obstacles[k].positions_at(0.0);
    for (const Vec3& p : x) mean += p;
    mean /= static_cast<double>(x.size());
    EXPECT_LT(std::hypot(mean.x() - copies[k].position.x(), mean.z() - copies[k].position.z()), 0.3) << k;
    // So does its dress.
    Vec3 dress = Vec3::Zero();
    for (NodeId n : s.garments[k].mesh.nodes()) dress += s.garments[k].mesh.x(n);
    dress /= static_cast<double>(s.garments[k].mesh.num_nodes());
    EXPECT_LT(std::hypot(dress.x() - copies[k].position.x(), dress.z() - copies[k].position.z()), 0.3) << k;
  }
  EXPECT_EQ(split_groups(s).size(), 3u);
}

// A template's mistakes are named where they are written, with the copy they were found in.
TEST(Crowd, ErrorsNameTheTemplateAndTheCopy) {
  const std::string dir = VDCLOTH_SOURCE_DIR;
  const std::string character = R"("character": {"motion": ")" + dir + R"(/motions/dance.bvh", "resolution": 0.05})";
  auto message = [&](const std::string& garment) {
    const fs::path path = write_crowd_scene("bad", R"({"name": "d", "count": 2, "layout": {"grid": {}}, "template": {)" + character +
                                                       R"(, "garments": [)" + garment + "]}}");
    std::string what;
    try {
      load_scene(path.string());
    } catch (const InputError& e) {
      what = e.what();
    }
    fs::remove_all(path.parent_path());
    return what;
  };
  EXPECT_NE(message(R"({"name": "dress", "group": "g", "mesh": {"dress": {}}, "material": "x.json"})").find("crowds[0].template.garments[0].group"),
            std::string::npos);
  EXPECT_NE(message(R"({"name": "dress", "mesh": {"dress": {}}, "material": "missing.json"})").find("crowds[0].template.garments[0][d01].material"),
            std::string::npos);
}

}  // namespace
}  // namespace vdc
