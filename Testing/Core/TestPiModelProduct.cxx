// SPDX-License-Identifier: BSD-3-Clause
// pisurf::MultiplyModels and RenameParameter: the product of models that "Pi Product"
// meshes.
#include "PiModel.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
pisurf::Model Parse(const std::string& text)
{
  pisurf::Model m;
  std::string error;
  EXPECT_TRUE(pisurf::ParseModel(text, m, error)) << error;
  return m;
}
}

TEST(ModelProduct, RenameParameterWholeNamesOnly)
{
  EXPECT_EQ(
    pisurf::RenameParameter("(x-a)^2+ab*a2+a*2e-3+a", "a", "a_2"), "(x-a_2)^2+ab*a2+a_2*2e-3+a_2");
  EXPECT_EQ(pisurf::RenameParameter("1e5*e+e", "e", "f"), "1e5*f+f");
  EXPECT_EQ(pisurf::RenameParameter("", "a", "b"), "");
}

TEST(ModelProduct, ConcatenatesPrimitivesWithOneBlending)
{
  const auto a = Parse(R"({"pisurf": 1, "blending": 3,
    "primitives": [{"type": "sphere", "center": [1, 0, 0], "radius": 1}]})");
  const auto b = Parse(R"({"pisurf": 1, "blending": 7,
    "primitives": [{"type": "torus", "major_radius": 2, "minor_radius": 0.5},
                   {"type": "ellipsoid", "radii": [1, 2, 3]}]})");
  pisurf::Model p;
  std::string error;
  ASSERT_TRUE(pisurf::MultiplyModels({ a, b }, 0.25, p, error)) << error;
  ASSERT_EQ(p.Primitives.size(), 3u);
  EXPECT_EQ(p.Blending, 0.25);
  EXPECT_EQ(p.Primitives[0].Type, pisurf::PrimitiveType::Sphere);
  EXPECT_EQ(p.Primitives[1].Type, pisurf::PrimitiveType::Torus);
  EXPECT_EQ(p.Primitives[2].Type, pisurf::PrimitiveType::Ellipsoid);
  // Bounded primitives only: no bounds (automatic, growing with r).
  EXPECT_FALSE(p.HasBounds);
  pisurf::Model again;
  EXPECT_TRUE(pisurf::ParseModel(pisurf::WriteModel(p), again, error)) << error;
}

TEST(ModelProduct, BoundsAreTheUnionOfTheUnboundedModels)
{
  const auto plane = Parse(R"({"pisurf": 1, "blending": 0, "bounds": [-1, 1, -1, 1, -1, 1],
    "primitives": [{"type": "plane", "normal": [0, 0, 1]}]})");
  const auto cylinder = Parse(R"({"pisurf": 1, "blending": 0, "bounds": [0, 3, -2, 0, -1, 0.5],
    "primitives": [{"type": "cylinder", "radius": 0.5}]})");
  // A bounded model's (meshed) bounds do not count.
  const auto sphere = Parse(R"({"pisurf": 1, "blending": 0, "bounds": [-9, 9, -9, 9, -9, 9],
    "primitives": [{"type": "sphere", "radius": 1}]})");
  pisurf::Model p;
  std::string error;
  ASSERT_TRUE(pisurf::MultiplyModels({ plane, sphere, cylinder }, 1, p, error)) << error;
  ASSERT_TRUE(p.HasBounds);
  const double expected[6] = { -1, 3, -2, 1, -1, 1 };
  for (int i = 0; i < 6; ++i)
  {
    EXPECT_EQ(p.Bounds[i], expected[i]) << i;
  }
}

TEST(ModelProduct, ClashingParametersAreRenamed)
{
  const auto a = Parse(R"({"pisurf": 1, "blending": 0, "bounds": [-3, 3, -3, 3, -3, 3],
    "parameters": {"a": 1, "b": 2},
    "primitives": [{"type": "polynomial", "expression": "(x-a)^2+y^2+z^2-b"}]})");
  const auto b = Parse(R"({"pisurf": 1, "blending": 0, "bounds": [-3, 3, -3, 3, -3, 3],
    "parameters": {"a": 5, "b": 2, "a_2": 7},
    "primitives": [{"type": "polynomial", "expression": "(x-a)^2+(y-a_2)^2+z^2-b"}]})");
  pisurf::Model p;
  std::string error;
  ASSERT_TRUE(pisurf::MultiplyModels({ a, b }, 0, p, error)) << error;
  EXPECT_EQ(p.Parameters.size(), 4u);
  EXPECT_EQ(p.Parameters.at("a"), 1);
  EXPECT_EQ(p.Parameters.at("b"), 2);
  EXPECT_EQ(p.Parameters.at("a_2"), 7);
  EXPECT_EQ(p.Parameters.at("a_3"), 5);
  EXPECT_EQ(p.Primitives[1].Expression, "(x-a_3)^2+(y-a_2)^2+z^2-b");
  // Each primitive keeps its function: the second is centred at (5, 7, 0).
  pisurf::PolynomialFactor f;
  ASSERT_TRUE(pisurf::BuildFactor(p.Primitives[1], p.Parameters, f, error)) << error;
  const double c[3] = { 5, 7, 0 };
  EXPECT_DOUBLE_EQ(f.Evaluate(c), -2);
}

TEST(ModelProduct, Errors)
{
  pisurf::Model p;
  std::string error;
  EXPECT_FALSE(pisurf::MultiplyModels({}, 0.25, p, error));
  EXPECT_NE(error.find("no factors"), std::string::npos) << error;
  const auto a = Parse(R"({"pisurf": 1, "blending": 0,
    "primitives": [{"type": "sphere", "radius": 1}]})");
  EXPECT_FALSE(pisurf::MultiplyModels({ a }, std::nan(""), p, error));
  pisurf::Model none;
  EXPECT_FALSE(pisurf::MultiplyModels({ a, none }, 0.25, p, error));
  EXPECT_NE(error.find("model 2"), std::string::npos) << error;
}
