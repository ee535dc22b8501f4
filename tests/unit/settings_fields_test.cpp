// The table of WorldSettings fields: it covers the struct, its keys are unique, and every range it
// states is what World::checkSettings enforces, naming the field.
#include <gtest/gtest.h>
#include <sandphys/sandphys.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "support/test_world.h"

namespace sandphys {
namespace {

// The bytes of WorldSettings the field's accessor reaches.
std::pair<std::size_t, std::size_t> bytesOf(const SettingField& field, WorldSettings& s) {
  const auto* base = reinterpret_cast<const unsigned char*>(&s);
  switch (field.kind) {
    case SettingField::Kind::Real:
      return {reinterpret_cast<const unsigned char*>(field.real(s)) - base, sizeof(float)};
    case SettingField::Kind::Count:
      return {reinterpret_cast<const unsigned char*>(field.count(s)) - base, sizeof(std::uint32_t)};
    case SettingField::Kind::Flag:
      return {reinterpret_cast<const unsigned char*>(field.flag(s)) - base, sizeof(bool)};
    case SettingField::Kind::Law:
      return {reinterpret_cast<const unsigned char*>(field.law(s)) - base, sizeof(ContactLaw)};
  }
  return {0, 0};
}

TEST(SettingFields, CoverEveryMemberOfWorldSettingsOnce) {
  WorldSettings s;
  std::vector<int> owner(sizeof(WorldSettings), -1);
  std::set<std::string> keys, members;
  const auto fields = worldSettingFields();
  for (std::size_t i = 0; i < fields.size(); ++i) {
    EXPECT_TRUE(keys.insert(fields[i].key).second) << "key twice: " << fields[i].key;
    EXPECT_TRUE(members.insert(fields[i].member).second) << "member twice: " << fields[i].member;
    EXPECT_EQ(findWorldSettingField(fields[i].key), &fields[i]);
    const auto [offset, size] = bytesOf(fields[i], s);
    ASSERT_LE(offset + size, sizeof(WorldSettings)) << fields[i].member;
    for (std::size_t b = offset; b < offset + size; ++b) {
      EXPECT_EQ(owner[b], -1) << fields[i].member << " shares a byte with another field";
      owner[b] = int(i);
    }
  }
  // A byte no field reaches is padding only beside a flag (bools share a 4-byte word): a member
  // of 4 bytes or more missing from the table leaves a whole word unreached and fails here.
  for (std::size_t word = 0; word < sizeof(WorldSettings); word += 4) {
    bool reached = false, flag = false;
    for (std::size_t b = word; b < word + 4 && b < sizeof(WorldSettings); ++b) {
      if (owner[b] < 0) continue;
      reached = true;
      flag = flag || fields[owner[b]].kind == SettingField::Kind::Flag;
    }
    EXPECT_TRUE(reached && (flag || owner[word] >= 0))
        << "bytes " << word << "-" << word + 3 << " of WorldSettings are in no SettingField";
  }
  EXPECT_EQ(findWorldSettingField("no_such_field"), nullptr);
}

// A value just outside the field's range that its type can hold (NaN for an unbounded real).
double outside(const SettingField& field) {
  const bool real = field.kind == SettingField::Kind::Real;
  if (std::isfinite(field.min) && (real || field.minOpen || field.min >= 1.0))
    return field.minOpen ? field.min : field.min - 1.0;
  if (std::isfinite(field.max)) return field.maxOpen ? field.max : field.max + 1.0;
  return std::numeric_limits<double>::quiet_NaN();
}

void set(const SettingField& field, WorldSettings& s, double value) {
  switch (field.kind) {
    case SettingField::Kind::Real:
      *field.real(s) = float(value);
      break;
    case SettingField::Kind::Count:
      *field.count(s) = std::uint32_t(value);
      break;
    case SettingField::Kind::Flag:
      *field.flag(s) = value != 0.0;
      break;
    case SettingField::Kind::Law:
      *field.law(s) = ContactLaw(unsigned(value));
      break;
  }
}

TEST(SettingFields, TheWorldRefusesEachValueOutsideTheTableRangeNamingTheField) {
  int checked = 0;
  for (const SettingField& field : worldSettingFields()) {
    if (field.kind == SettingField::Kind::Flag) continue;
    const double bad = outside(field);
    ASSERT_TRUE(field.kind == SettingField::Kind::Real || std::isfinite(bad)) << field.member;
    WorldSettings s;
    set(field, s, bad);
    EXPECT_FALSE(field.accepts(field.valueIn(s))) << field.member;
    const std::string message = testing::errorMessageOf([&] { World::checkSettings(s); });
    EXPECT_NE(message.find(std::string("WorldSettings.") + field.member), std::string::npos)
        << field.member << " = " << bad << ": " << message;
    EXPECT_NE(message.find(field.rangeText()), std::string::npos) << message;
    ++checked;
  }
  EXPECT_GE(checked, 20);
  // And the defaults pass every range.
  const WorldSettings defaults;
  for (const SettingField& field : worldSettingFields())
    EXPECT_TRUE(field.accepts(field.valueIn(defaults))) << field.member;
}

TEST(SettingFields, RangeTextsReadAsTheErrorsState) {
  EXPECT_EQ(findWorldSettingField("density")->rangeText(), "must be finite and > 0 (kg/m^3)");
  EXPECT_EQ(findWorldSettingField("poisson_ratio")->rangeText(), "must be in [0, 0.5)");
  EXPECT_EQ(findWorldSettingField("restitution")->rangeText(), "must be in (0, 1]");
  EXPECT_EQ(findWorldSettingField("max_bodies")->rangeText(), "must be >= 1");
  EXPECT_EQ(findWorldSettingField("gravity_y")->rangeText(), "must be finite (m/s^2)");
}

}  // namespace
}  // namespace sandphys
