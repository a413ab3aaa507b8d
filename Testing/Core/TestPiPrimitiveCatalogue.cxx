// SPDX-License-Identifier: BSD-3-Clause
// The primitive catalogue's own consistency: a catalogue entry with an invalid default,
// a repeated key or a widget bound to a missing parameter fails here, not at run time.
// (The XML and the documentation against it: Testing/Python/TestPiPrimitiveCatalogue.py.)
#include "PiModel.h"
#include "PiPrimitiveCatalogue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>

using namespace pisurf;

namespace
{
bool IsParameterOf(const PrimitiveInfo& entry, const char* property)
{
  return property && FindParameter(entry, property) &&
    std::string(FindParameter(entry, property)->Property) == property;
}
}

TEST(PiPrimitiveCatalogue, EntriesFollowTheTypeEnumeration)
{
  const auto& catalogue = PrimitiveCatalogue();
  ASSERT_EQ(catalogue.size(), static_cast<size_t>(PrimitiveType::NumberOfTypes));
  for (size_t i = 0; i < catalogue.size(); ++i)
  {
    EXPECT_EQ(static_cast<size_t>(catalogue[i].Type), i) << catalogue[i].Key;
    EXPECT_EQ(&CatalogueEntry(catalogue[i].Type), &catalogue[i]);
    EXPECT_TRUE(IsPrimitiveType(static_cast<int>(i)));
  }
  EXPECT_FALSE(IsPrimitiveType(-1));
  EXPECT_FALSE(IsPrimitiveType(static_cast<int>(catalogue.size())));
}

TEST(PiPrimitiveCatalogue, KeysAndLabelsAreUnique)
{
  std::set<std::string> names;
  // The frame's keys and properties, which every type has: no parameter may take them.
  const std::set<std::string> frame = { "type", "name", "center", "axis", "rotation", "scale",
    "negate", "Type", "Name", "Center", "Axis", "RotationAxis", "RotationAngle", "Orientation",
    "Scale", "Negate" };
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    // A type is read by either spelling: no key may be another type's label.
    EXPECT_TRUE(names.insert(e.Key).second) << "type key " << e.Key << " repeated";
    if (std::string(e.Label) != e.Key)
    {
      EXPECT_TRUE(names.insert(e.Label).second) << "type label " << e.Label << " repeated";
    }
    std::set<std::string> keys, properties;
    for (const ParameterInfo& p : e.Parameters)
    {
      EXPECT_TRUE(keys.insert(p.Key).second) << e.Key << ": key " << p.Key << " repeated";
      EXPECT_TRUE(properties.insert(p.Property).second)
        << e.Key << ": property " << p.Property << " repeated";
      EXPECT_EQ(frame.count(p.Key) + frame.count(p.Property), 0u)
        << e.Key << ": " << p.Key << " is a key every primitive has";
    }
  }
}

TEST(PiPrimitiveCatalogue, ParametersAreWellFormed)
{
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    EXPECT_NE(e.Build, nullptr) << e.Key;
    for (const ParameterInfo& p : e.Parameters)
    {
      const std::string where = std::string(e.Key) + "." + p.Key;
      EXPECT_TRUE(p.Label && *p.Label) << where;
      EXPECT_TRUE(p.Tooltip && *p.Tooltip) << where;
      EXPECT_NE(p.Unit, nullptr) << where;
      EXPECT_EQ(p.Numbers != nullptr, p.Kind == ParameterKind::Number) << where;
      EXPECT_EQ(p.Integer != nullptr, p.Kind == ParameterKind::Integer) << where;
      EXPECT_EQ(p.Text != nullptr, p.Kind == ParameterKind::Text) << where;
      EXPECT_EQ(p.Kind == ParameterKind::Text, p.Rule == Constraint::Expression) << where;
      EXPECT_EQ(p.DefaultText != nullptr, p.Kind == ParameterKind::Text) << where;
      EXPECT_GE(p.Count, 1) << where;
      EXPECT_LE(p.Count, p.Kind == ParameterKind::Number ? 3 : 1) << where;
      // The editor's row summary names numbers by symbols: one, or one per component.
      if (p.Kind != ParameterKind::Text)
      {
        ASSERT_TRUE(p.Symbol && *p.Symbol) << where;
        const std::string symbol = p.Symbol;
        const size_t words = 1 + std::count(symbol.begin(), symbol.end(), ' ');
        EXPECT_TRUE(words == 1 || words >= static_cast<size_t>(p.Count)) << where;
      }
    }
  }
}

TEST(PiPrimitiveCatalogue, EveryDefaultSatisfiesItsConstraint)
{
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    const PrimitiveSpec s = DefaultPrimitive(e.Type);
    for (const ParameterInfo& p : e.Parameters)
    {
      std::string error;
      EXPECT_TRUE(CheckParameter(s, p, error)) << e.Key << ": " << error;
      if (p.Kind == ParameterKind::Number)
      {
        for (int i = 0; i < p.Count; ++i)
        {
          EXPECT_TRUE(Allows(p.Rule, p.Default[i])) << e.Key << "." << p.Key << "[" << i << "]";
        }
      }
      else if (p.Kind == ParameterKind::Integer)
      {
        EXPECT_TRUE(Allows(p.Rule, p.Default[0])) << e.Key << "." << p.Key;
      }
      else
      {
        EXPECT_TRUE(p.DefaultText && *p.DefaultText) << e.Key << "." << p.Key;
      }
    }
  }
}

TEST(PiPrimitiveCatalogue, BuildFactorSucceedsOnEveryDefault)
{
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    const PrimitiveSpec s = DefaultPrimitive(e.Type);
    PolynomialFactor f;
    std::string error;
    ASSERT_TRUE(BuildFactor(s, ParameterMap(), f, error)) << e.Key << ": " << error;
    EXPECT_EQ(f.Bounded, e.Bounded) << e.Key;
    EXPECT_GE(f.Poly.GetDegree(), 1) << e.Key;
  }
}

TEST(PiPrimitiveCatalogue, ADefaultOfEveryTypeRoundTripsThroughTheModel)
{
  Model m;
  m.HasBounds = true;
  const double box[6] = { -2, 2, -2, 2, -2, 2 };
  std::copy(box, box + 6, m.Bounds);
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    m.Primitives.push_back(DefaultPrimitive(e.Type));
  }
  const std::string text = WriteModel(m);
  Model back;
  std::string error;
  ASSERT_TRUE(ParseModel(text, back, error)) << error;
  EXPECT_EQ(WriteModel(back), text);
}

TEST(PiPrimitiveCatalogue, SharedKeysShareStorageAndDefaults)
{
  // Parameters of the same key, in different types, are one member of PrimitiveSpec:
  // same property, kind and default (the defaults vtkPiPrimitive starts with).
  std::map<std::string, const ParameterInfo*> first;
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    for (const ParameterInfo& p : e.Parameters)
    {
      auto it = first.emplace(p.Key, &p).first;
      const ParameterInfo& q = *it->second;
      EXPECT_STREQ(p.Property, q.Property) << e.Key << "." << p.Key;
      EXPECT_EQ(p.Kind, q.Kind) << e.Key << "." << p.Key;
      PrimitiveSpec a;
      if (p.Kind == ParameterKind::Number)
      {
        EXPECT_EQ(p.Numbers(a), q.Numbers(a)) << e.Key << "." << p.Key;
        for (int i = 0; i < std::min(p.Count, q.Count); ++i)
        {
          EXPECT_EQ(p.Default[i], q.Default[i]) << e.Key << "." << p.Key;
        }
      }
      else if (p.Kind == ParameterKind::Integer)
      {
        EXPECT_EQ(p.Integer(a), q.Integer(a)) << e.Key << "." << p.Key;
        EXPECT_EQ(p.Default[0], q.Default[0]) << e.Key << "." << p.Key;
      }
      else
      {
        EXPECT_EQ(p.Text(a), q.Text(a)) << e.Key << "." << p.Key;
      }
    }
  }
  // PrimitiveSpec's own member defaults are the catalogue's (numbers: a parsed model
  // keeps them for the keys its type does not have).
  PrimitiveSpec plain;
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    for (const ParameterInfo& p : e.Parameters)
    {
      if (p.Kind == ParameterKind::Number)
      {
        for (int i = 0; i < p.Count; ++i)
        {
          EXPECT_EQ(p.Numbers(plain)[i], p.Default[i]) << e.Key << "." << p.Key;
        }
      }
      else if (p.Kind == ParameterKind::Integer)
      {
        EXPECT_EQ(*p.Integer(plain), p.Default[0]) << e.Key << "." << p.Key;
      }
    }
  }
}

TEST(PiPrimitiveCatalogue, WidgetsEditParametersOfTheirType)
{
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    const bool size = e.Widget == WidgetKind::Sphere || e.Widget == WidgetKind::Cylinder ||
      e.Widget == WidgetKind::Box;
    const bool direction = e.Widget == WidgetKind::Cylinder || e.Widget == WidgetKind::Plane;
    EXPECT_EQ(e.WidgetSize != nullptr, size) << e.Key;
    EXPECT_EQ(e.WidgetDirection != nullptr, direction) << e.Key;
    if (e.WidgetSize)
    {
      ASSERT_TRUE(IsParameterOf(e, e.WidgetSize)) << e.Key << ": " << e.WidgetSize;
      const ParameterInfo& p = *FindParameter(e, e.WidgetSize);
      EXPECT_EQ(p.Kind, ParameterKind::Number) << e.Key;
      // A radius, or (a box) up to three semi-axes; the editor's box needs all three.
      EXPECT_EQ(p.Count == 1, e.Widget != WidgetKind::Box) << e.Key;
      if (e.Widget == WidgetKind::Box && e.Bounded)
      {
        EXPECT_EQ(p.Count, 3) << e.Key;
      }
    }
    // The direction is the type's own vector, or the frame's Axis.
    if (e.WidgetDirection && std::string(e.WidgetDirection) != "Axis")
    {
      ASSERT_TRUE(IsParameterOf(e, e.WidgetDirection)) << e.Key << ": " << e.WidgetDirection;
      EXPECT_EQ(FindParameter(e, e.WidgetDirection)->Count, 3) << e.Key;
    }
  }
}

TEST(PiPrimitiveCatalogue, ConstraintsGiveTheMessagesOfBuildFactor)
{
  PrimitiveSpec s = DefaultPrimitive(PrimitiveType::Superellipsoid);
  s.Radii[1] = -1;
  PolynomialFactor f;
  std::string error;
  EXPECT_FALSE(BuildFactor(s, ParameterMap(), f, error));
  EXPECT_EQ(error, "radii[1] must be a positive finite number");
  s.Radii[1] = 1;
  s.Exponent = 3;
  EXPECT_FALSE(BuildFactor(s, ParameterMap(), f, error));
  EXPECT_EQ(error, "exponent must be an even integer from 2 to 64 (got 3)");
  s = DefaultPrimitive(PrimitiveType::Plane);
  s.Normal[2] = 0;
  EXPECT_FALSE(BuildFactor(s, ParameterMap(), f, error));
  EXPECT_EQ(error, "normal must be a non-zero vector of finite numbers");
  s = DefaultPrimitive(PrimitiveType::Cone);
  s.Angle = 90;
  EXPECT_FALSE(BuildFactor(s, ParameterMap(), f, error));
  EXPECT_EQ(error, "angle must be a half-angle in degrees strictly between 0 and 90");
}

TEST(PiPrimitiveCatalogue, JSONListsEveryType)
{
  const std::string json = CatalogueJSON();
  for (const PrimitiveInfo& e : PrimitiveCatalogue())
  {
    EXPECT_NE(json.find(std::string("\"") + e.Key + "\""), std::string::npos) << e.Key;
  }
}
