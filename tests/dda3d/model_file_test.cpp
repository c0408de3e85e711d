// A DDA model saved by dda3d::saveModel reads back bit for bit; a file that is not one gives
// an error naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "dda3d/model_file.h"
#include "scenarios/dda_scenes.h"

namespace rockmass::dda3d {
namespace {

using geometry::Vec3;

std::string bytesOf(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A model with something in every field the file holds.
DdaModel everyField() {
  DdaModel m;
  scenes::setRock(m, 35.0);
  m.joints.push_back({0.5, 2e5, 1e5, JointModel::Brittle});
  m.blocks.push_back(scenes::boxBlock({-2, -2, -1}, {2, 2, 0}, 0, true));
  DdaBlock b = scenes::boxBlock({0, 0, 0}, {1, 1, 1}, 0, false);
  b.pieces.push_back(geometry::boxPolyhedron({Vec3(1, 0, 0), Vec3(1.5, 1, 1)}));
  b.face_joints = {{-1, 0, 1, -1, 0, 1}, {1, 1, 1, 1, 1, 1}};
  b.structure = 2;
  b.contact_point_spacing = 0.25;
  b.initial_stress << -1e5, -2e5, -3e5, 1e3, 2e3, 3e3;
  b.initial_velocity = Vec3(0.1, 0.2, 0.3);
  b.initial_angular_velocity = Vec3(-0.01, 0.02, -0.03);
  m.blocks.push_back(b);
  m.default_joint = 1;
  m.gravity = Vec3(0, 0, -9.81);
  m.seismic = Vec3(0.981, 0, 0);
  m.monitors.push_back({"toe \"A\"", Vec3(0.5, 0.5, 0.5), 1});
  m.point_loads.push_back({1, Vec3(0.5, 0.5, 1), Vec3(0, 0, -1e4)});
  m.fixed_points.push_back({1, Vec3(0, 0, 0), Vec3(0, 1, 0)});
  m.fixed_points.push_back({1, Vec3(1, 0, 0), Vec3::Zero(), Vec3(1, 0, -1e-6)});  // settled
  DdaPressure p = hydrostaticPressure(1, 1, 3, 2.5, 9810, true);
  p.pore = true;
  p.head_gradient = Vec3(-0.01, 0, 0);
  p.within.push_back({Vec3(1, 0, 0), 1.25});
  m.pressures.push_back(p);
  m.hydrodynamic.push_back({1, 0, 2, 3.0, 3.0, 0.1, 9810});
  DdaBolt bolt;
  bolt.block_a = 1, bolt.point_a = Vec3(0.5, 0.5, 0.5), bolt.block_b = -1;
  bolt.point_b = Vec3(0.5, 0.5, -0.5), bolt.stiffness = 1e7, bolt.pretension = 1e4;
  bolt.yield_force = 2e5, bolt.broken = true;
  m.bolts.push_back(bolt);
  return m;
}

TEST(ModelFile, ReadsBackBitForBit) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rockmass_model_file";
  std::filesystem::create_directories(dir);
  const DdaModel model = everyField();
  saveModel(model, dir / "a.model");
  const DdaModel back = loadModel(dir / "a.model");
  // Saved again, the same bytes: every field the writer holds came back.
  saveModel(back, dir / "b.model");
  EXPECT_EQ(bytesOf(dir / "a.model"), bytesOf(dir / "b.model"));
  // And the fields are the model's (a writer and reader that agreed on a wrong layout would
  // pass the line above).
  ASSERT_EQ(back.blocks.size(), 2u);
  EXPECT_EQ(back.blocks[1].pieces[1].vertices, model.blocks[1].pieces[1].vertices);
  EXPECT_EQ(back.blocks[1].pieces[1].faces, model.blocks[1].pieces[1].faces);
  EXPECT_EQ(back.blocks[1].face_joints, model.blocks[1].face_joints);
  EXPECT_EQ(back.blocks[1].contact_point_spacing, 0.25);
  EXPECT_FALSE(back.blocks[0].contact_point_spacing.has_value());
  EXPECT_TRUE(back.blocks[0].fixed);
  EXPECT_EQ(back.blocks[1].initial_stress, model.blocks[1].initial_stress);
  EXPECT_EQ(back.blocks[1].initial_angular_velocity, model.blocks[1].initial_angular_velocity);
  EXPECT_EQ(back.joints[1].model, JointModel::Brittle);
  EXPECT_EQ(back.default_joint, 1);
  EXPECT_EQ(back.seismic, model.seismic);
  EXPECT_EQ(back.monitors[0].name, "toe \"A\"");
  EXPECT_EQ(back.fixed_points[0].direction, Vec3(0, 1, 0));
  EXPECT_FALSE(back.fixed_points[0].current.has_value());
  ASSERT_TRUE(back.fixed_points[1].current.has_value());
  EXPECT_EQ(*back.fixed_points[1].current, Vec3(1, 0, -1e-6));
  EXPECT_TRUE(back.pressures[0].uplift && back.pressures[0].pore);
  EXPECT_EQ(back.pressures[0].within[0].offset, 1.25);
  EXPECT_EQ(back.hydrodynamic[0].k_h, 0.1);
  EXPECT_EQ(back.bolts[0].yield_force, 2e5);
  EXPECT_TRUE(back.bolts[0].broken);
  EXPECT_FALSE(std::filesystem::exists(dir / "a.model.partial"));
  std::filesystem::remove_all(dir);
}

TEST(ModelFile, AnotherFileIsRefusedByName) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "rockmass_model_bad";
  std::filesystem::create_directories(dir);
  saveModel(everyField(), dir / "good.model");
  const std::string good = bytesOf(dir / "good.model");
  const auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
    return dir / name;
  };
  const auto message = [](const std::filesystem::path& path) {
    try {
      loadModel(path);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const auto truncated = write("truncated.model", good.substr(0, good.size() / 2));
  EXPECT_NE(message(truncated).find("truncated.model: not a DDA model file"), std::string::npos)
      << message(truncated);
  const auto other = write("scene.yaml", "name: not a model\n");
  EXPECT_NE(message(other).find("scene.yaml: not a DDA model file"), std::string::npos);
  EXPECT_NE(message(dir / "absent.model").find("cannot open"), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rockmass::dda3d
