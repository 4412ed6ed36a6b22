#include "config/key_suggestion.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.hpp"
#include "config/config_json.hpp"

namespace dsswarm {
namespace {

TEST(EditDistance, CountsInsertionsDeletionsAndSubstitutionsIgnoringCase) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("evaluations", "evaluatons"), 1u);  // a deletion
  EXPECT_EQ(edit_distance("levels", "lveels"), 2u);           // a swap is two
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("Hit_Occupied", "hit_occupied"), 0u);
  EXPECT_EQ(edit_distance("resolution", "seed"), edit_distance("seed", "resolution"));
}

const KnownKeys kKnown{{"map", {"resolution", "levels"}},
                       {"evidence", {"hit_occupied", "pass_free"}},
                       {"matcher", {"evaluations", "seed"}},
                       {"loop", {"evidence"}}};

TEST(SuggestKey, NamesTheKnownKeyAWrongOneMostLikelyMeant) {
  EXPECT_EQ(suggest_key(kKnown, "matcher", "evaluatons"), "matcher.evaluations");  // a typo
  EXPECT_EQ(suggest_key(kKnown, "map", "seed"), "matcher.seed");                   // the wrong section
  EXPECT_EQ(suggest_key(kKnown, "map", "evidence"), "evidence");  // a section as a key (before loop.evidence)
  EXPECT_EQ(suggest_key(kKnown, "map", "pass_fre"), "evidence.pass_free");         // a typo, wrong section
  EXPECT_EQ(suggest_key(kKnown, "mapp", ""), "map");                               // a section's typo
  EXPECT_EQ(suggest_key(kKnown, "map", "Levels"), "map.levels");
}

TEST(SuggestKey, SuggestsNothingWhenNoKnownKeyIsClose) {
  EXPECT_EQ(suggest_key(kKnown, "map", "colour"), std::nullopt);
  EXPECT_EQ(suggest_key(kKnown, "map", "x"), std::nullopt);
  EXPECT_EQ(suggest_key(kKnown, "network", ""), std::nullopt);
  EXPECT_EQ(suggest_key({}, "map", "levels"), std::nullopt);
}

// The configuration loader's messages carry the suggestion, for the real table.
std::string error_of(const char* text) {
  SwarmConfig c;
  try {
    parse_config(text, "robot.json", c);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SuggestKey, TheConfigLoaderSaysWhatAnUnknownKeyMostLikelyMeant) {
  EXPECT_EQ(error_of(R"({"matcher": {"evaluatons": 10}})"),
            "robot.json: unknown key 'matcher.evaluatons' (did you mean 'matcher.evaluations'?)");
  EXPECT_EQ(error_of(R"({"map": {"evidence": {"hit_occupied": 0.3}}})"),
            "robot.json: unknown key 'map.evidence' (did you mean the section 'evidence'? it stands at the top level)");
  EXPECT_EQ(error_of(R"({"maps": {}})"), "robot.json: unknown section 'maps' (did you mean 'map'?)");
  EXPECT_EQ(error_of(R"({"map": {"zzzzzzzzzzzz": 1}})"), "robot.json: unknown key 'map.zzzzzzzzzzzz'");
}

}  // namespace
}  // namespace dsswarm
