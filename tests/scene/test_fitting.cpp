// Garments fitted to the figure wearing them: heights through the skeleton's landmarks, radii
// keeping the ease the garment has on the project's figure, the same rows cut; and the build
// that keeps a slender figure's arms clear of its body.
#include <gtest/gtest.h>

#include <stdexcept>

#include "scene/body.hpp"
#include "scene/bvh_motion.hpp"
#include "scene/figure.hpp"
#include "scene/fitting.hpp"
#include "scene/garments.hpp"

namespace vdc {
namespace {

constexpr double kResolution = 0.03;

Motion at_rest(const Skeleton& skeleton) {
  Motion m;
  m.skeleton = skeleton;
  m.frames.assign(1, std::vector<double>(static_cast<std::size_t>(skeleton.num_channels), 0.0));
  return m;
}

FigureMeasure measured(const Motion& motion, double build) {
  const Body body(motion, BodyParams{build, kResolution, 0.04});
  const Pose rest = Body::rest_pose(motion.skeleton);
  return measure_figure(motion, rest, body.rest_mesh(), body.skin(rest), body.main_joints());
}

TEST(Fitting, TheProjectsFigureWearsGarmentsAsGiven) {
  const FigureMeasure reference = measured(at_rest(figure_skeleton()), 1.0);
  // The project's figure: toes 0.01, knees 0.48, hips 0.90, shoulders 1.42, head 1.56 m.
  EXPECT_NEAR(reference.landmarks[0], 0.01, 1e-12);
  EXPECT_NEAR(reference.landmarks[1], 0.48, 1e-12);
  EXPECT_NEAR(reference.landmarks[2], 0.90, 1e-12);
  EXPECT_NEAR(reference.landmarks[3], 1.42, 1e-12);
  EXPECT_NEAR(reference.landmarks[4], 1.56, 1e-12);
  EXPECT_NEAR(reference.shoulder_half_width, 0.18, 1e-12);
  // The dance's skeleton, as read from its BVH file, is the same figure.
  Motion dance = read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/dance.bvh");
  dance.frames.resize(1);
  EXPECT_TRUE(GarmentFit(reference, measured(dance, 1.0)).identity());
  EXPECT_FALSE(GarmentFit(reference, measured(at_rest(figure_skeleton(1.6)), 1.0)).identity());
  EXPECT_FALSE(GarmentFit(reference, measured(dance, 1.2)).identity());
}

TEST(Fitting, HeightsFollowTheLandmarksAndTheEaseIsKept) {
  const FigureMeasure reference = measured(at_rest(figure_skeleton()), 1.0);
  // A figure of 1.6 m, every bone 1.6 / 1.75 as long, limbs 1.2 times as thick.
  const GarmentFit fit(reference, measured(at_rest(figure_skeleton(1.6)), 1.2));
  const double s = 1.6 / 1.75;
  for (double y : {0.0, 0.45, 1.05, 1.32, 1.52, 2.0}) EXPECT_NEAR(fit.height(y), s * y, 1e-12) << y;

  const DressParams dress;
  const DressParams fitted = fit.fit(dress);
  EXPECT_NEAR(fitted.waist_height, s * dress.waist_height, 1e-12);
  EXPECT_NEAR(fitted.hem_height, s * dress.hem_height, 1e-12);
  EXPECT_NEAR(fitted.strap_rise, s * dress.strap_rise, 1e-12);
  EXPECT_NEAR(fitted.strap_x, s * dress.strap_x, 1e-12);  // the shoulders are s times as wide
  EXPECT_GT(fitted.bodice_radius, dress.bodice_radius + 0.01);
  // At every height the fitted garment is as far beyond the figure's body as the given one is
  // beyond the project's figure's, or farther.
  const FigureMeasure figure = measured(at_rest(figure_skeleton(1.6)), 1.2);
  auto ease_lost = [&](double y, double radius, double fitted_radius) {
    return (radius - reference.girth_at(y)) - (fitted_radius - figure.girth_at(fit.height(y)));
  };
  double most_lost = -1;
  for (double y = dress.waist_height; y <= dress.top_height; y += 0.005)
    most_lost = std::max(most_lost, ease_lost(y, dress.bodice_radius, fitted.bodice_radius));
  const double drop = dress.waist_height - dress.hem_height;
  for (double y = dress.hem_height; y <= dress.waist_height - 0.1 * drop; y += 0.005) {
    const double u = (dress.waist_height - y) / drop;
    most_lost = std::max(most_lost, ease_lost(y, dress.bodice_radius + u * (dress.hem_radius - dress.bodice_radius),
                                              fitted.bodice_radius + u * (fitted.hem_radius - fitted.bodice_radius)));
  }
  EXPECT_LE(most_lost, 1e-12);
  EXPECT_GT(most_lost, -1e-3);  // and no more than it must: some height keeps exactly its ease

  // Cut in the same rows: the same nodes in the same order.
  EXPECT_EQ(make_dress(fitted).positions.size(), make_dress(dress).positions.size());
  EXPECT_EQ(make_dress(fitted).faces.size(), make_dress(dress).faces.size());
  // A tube: its top ring keeps exactly its ease there, the cone below at least its ease, at
  // every height, for the whole ease and for a share of it.
  const TubeParams tube{48, 1.0, 0.185, 0.3, 0.36, 0.03};
  for (double share : {1.0, 0.3}) {
    const TubeParams fitted_tube = fit.fit(tube, share);
    EXPECT_EQ(fitted_tube.rows, with_rows(tube).rows);
    EXPECT_NEAR(fitted_tube.top_height, s * 1.0, 1e-12);
    EXPECT_NEAR(fitted_tube.bottom_height, s * 0.3, 1e-12);
    auto kept = [&](double y, double radius, double fitted_radius) {  // fitted ease less `share` of the given
      return (fitted_radius - figure.girth_at(fit.height(y))) - share * (radius - reference.girth_at(y));
    };
    EXPECT_NEAR(kept(1.0, tube.top_radius, fitted_tube.top_radius), 0, 1e-12) << share;
    double least = 1;
    for (double y = 0.3; y <= 1.0 - 0.07; y += 0.005) {
      const double u = (1.0 - y) / 0.7;
      least = std::min(least, kept(y, tube.top_radius + u * (tube.bottom_radius - tube.top_radius),
                                   fitted_tube.top_radius + u * (fitted_tube.bottom_radius - fitted_tube.top_radius)));
    }
    EXPECT_GE(least, -1e-12) << share;
    EXPECT_LT(least, 1e-3) << share;  // and the cone is no wider than it must be somewhere
  }
  // A share of the ease: the dress is narrower, its bodice by 0.7 of the given ease at its tightest.
  EXPECT_LT(fit.fit(dress, 0.3).bodice_radius, fitted.bodice_radius - 0.01);
}

TEST(Fitting, AFigureThatIsNotAHumanoidsSaysWhy) {
  Skeleton skeleton = figure_skeleton();
  for (Joint& j : skeleton.joints)
    if (j.name == "LeftLeg") j.name = "LeftTibia";  // a name no scheme gives the knee: the shape finds it
  EXPECT_NO_THROW(measured(at_rest(skeleton), 1.0));
  while (skeleton.joints.back().name != "RightUpLeg") skeleton.joints.pop_back();  // the right leg's joints are the last
  skeleton.joints.pop_back();
  skeleton.num_channels = skeleton.joints.back().first_channel + static_cast<int>(skeleton.joints.back().channels.size());
  try {
    measured(at_rest(skeleton), 1.0);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "its skeleton is not a humanoid's: no joint where two legs and a spine part (the hips) below one where two arms and a neck part (the chest)");
  }
}

TEST(Fitting, ASlenderFiguresBuildKeepsItsArmsClear) {
  // A torso bone straight up from (0, 1, 0) to (0, 1.5, 0), 0.13 m thick; collarbones out to
  // shoulders at x = +-0.15; upper arms from there down and out to (+-0.25, 1.1, 0), 0.05 to
  // 0.04 m thick. The shoulder is nearest the torso: 0.15 m between the axes, 0.18 m of radii,
  // so the arms keep 1 cm at a build of (0.15 - 0.01) / 0.18. (A neck, hands and legs make it a
  // humanoid; none comes nearer the arms.)
  Skeleton k;
  auto add = [&](const std::string& name, int parent, Vec3 offset, bool end = false) {
    Joint j;
    j.name = name;
    j.parent = parent;
    j.offset = offset;
    j.end_site = end;
    j.first_channel = k.num_channels;
    if (!end) j.channels = {Channel::ZRotation, Channel::XRotation, Channel::YRotation};
    k.num_channels += static_cast<int>(j.channels.size());
    k.joints.push_back(j);
    return static_cast<int>(k.joints.size()) - 1;
  };
  const int hips = add("Hips", -1, Vec3(0, 1, 0));
  const int spine = add("Spine", hips, Vec3(0, 0.5, 0));
  const int neck = add("Neck", spine, Vec3(0, 0.1, 0));
  add("Head_end", add("Head", neck, Vec3(0, 0.1, 0)), Vec3(0, 0.2, 0), true);
  for (int side : {1, -1}) {
    const std::string p = side > 0 ? "Left" : "Right";
    const int shoulder = add(p + "Shoulder", spine, Vec3(side * 0.02, 0, 0));
    const int arm = add(p + "Arm", shoulder, Vec3(side * 0.13, 0, 0));
    const int fore = add(p + "ForeArm", arm, Vec3(side * 0.1, -0.4, 0));
    add(p + "Hand_end", add(p + "Hand", fore, Vec3(side * 0.1, -0.3, 0)), Vec3(side * 0.03, -0.06, 0), true);
    const int leg = add(p + "Leg", add(p + "UpLeg", hips, Vec3(side * 0.08, -0.05, 0)), Vec3(0, -0.42, 0));
    add(p + "Foot_end", add(p + "Foot", leg, Vec3(0, -0.42, 0)), Vec3(0, -0.05, 0.12), true);
  }
  const Motion m = at_rest(k);
  EXPECT_NEAR(build_clearing_arms(m, {Body::rest_pose(k)}, 0.01), 0.14 / 0.18, 1e-12);
  // The project's motions keep their arms clear at full build in every frame.
  for (const char* name : {"dance", "karate"}) {
    const Motion motion = read_bvh(std::string(VDCLOTH_SOURCE_DIR) + "/motions/" + name + ".bvh");
    std::vector<Pose> poses;
    for (std::size_t f = 0; f < motion.frames.size(); ++f) poses.push_back(motion.frame_pose(f));
    EXPECT_EQ(build_clearing_arms(motion, poses, 0.01), 1.0) << name;
  }
}

TEST(Fitting, LayersFittedTogetherKeepTheirOrderAndShareOfTheGap) {
  // karate's layers (hakama, tunic, belt) on a figure of 1.6 m with limbs 1.2 times as thick,
  // at a third of their ease: fitted one by one, the belt (0.23 m, 1.5 to 2.5 cm outside the
  // tunic on the project's figure) keeps its ease over the waist only, while the tunic's bodice
  // keeps its own over the chest as well, and the belt ends inside the tunic.
  const FigureMeasure reference = measured(at_rest(figure_skeleton()), 1.0);
  const GarmentFit fit(reference, measured(at_rest(figure_skeleton(1.6)), 1.2));
  const TubeParams hakama{48, 1.0, 0.185, 0.3, 0.36, 0.03};
  DressParams tunic;
  tunic.bodice_radius = 0.205;
  tunic.top_height = 1.29;
  tunic.hem_height = 0.8;
  tunic.hem_radius = 0.265;
  const TubeParams belt{48, 1.06, 0.23, 0.99, 0.23, 0.025};
  const double share = 0.3;
  const std::vector<GarmentPattern> worn = {hakama, tunic, belt};
  const std::vector<GarmentPattern> together = fit.fit(worn, share);
  // Outside by at least the share of the gap at every height both cover; `least` is the smallest
  // margin over that, which the outer layer meets exactly somewhere.
  auto least_margin = [&](const GarmentPattern& outer, const GarmentPattern& inner, const GarmentPattern& outer_fitted,
                          const GarmentPattern& inner_fitted) {
    double least = 1;
    for (double y = 0.3; y <= 1.3; y += 0.005) {
      const auto ro = garment_radius(outer, y), ri = garment_radius(inner, y);
      const auto fo = garment_radius(outer_fitted, fit.height(y)), fi = garment_radius(inner_fitted, fit.height(y));
      if (!ro || !ri || !fo || !fi || *ri >= *ro) continue;
      least = std::min(least, *fo - *fi - share * (*ro - *ri));
    }
    return least;
  };
  const GarmentPattern alone_tunic = fit.fit(tunic, share), alone_belt = fit.fit(belt, share);
  EXPECT_LT(least_margin(belt, tunic, alone_belt, alone_tunic), -0.005);  // one by one: 5 mm and more inside
  EXPECT_GE(least_margin(belt, tunic, together[2], together[1]), -1e-12);
  EXPECT_LT(least_margin(belt, tunic, together[2], together[1]), 1e-9);  // its top ring, exactly
  EXPECT_GE(least_margin(tunic, hakama, together[1], together[0]), -1e-12);
  // The order the garments are given in changes nothing.
  const std::vector<GarmentPattern> reversed = fit.fit({belt, tunic, hakama}, share);
  EXPECT_EQ(std::get<TubeParams>(reversed[0]).top_radius, std::get<TubeParams>(together[2]).top_radius);
  EXPECT_EQ(std::get<DressParams>(reversed[1]).bodice_radius, std::get<DressParams>(together[1]).bodice_radius);
  // garment_radius: a dress's bodice above the waist, its skirt's cone below, nothing past the hem.
  EXPECT_EQ(*garment_radius(tunic, 1.2), 0.205);
  EXPECT_NEAR(*garment_radius(tunic, 0.8 + 0.5 * (tunic.waist_height - 0.8)), 0.235, 1e-12);
  EXPECT_FALSE(garment_radius(tunic, 0.79));
  EXPECT_FALSE(garment_radius(belt, 1.07));
}

}  // namespace
}  // namespace vdc
