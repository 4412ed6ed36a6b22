#include "eval/swarm_eval.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "common/errors.hpp"
#include "common/test_files.hpp"

namespace dsswarm {
namespace {

namespace fs = std::filesystem;

// The true path: straight along x, 1 m per second, from t = 100 (pose x = t − 100).
Pose2 world(double t) { return {t - 100.0, 0.0, 0.0}; }

// b's map frame in the world, and the estimate of it an encounter produced
// (10 cm off along the world's x).
const Pose2 kFrameB(2.0, 1.0, 0.5);
const Pose2 kFrameBEstimate = Pose2(0.1, 0.0, 0.0) * kFrameB;

// Agent a covers 100..105 in the world frame with a 1% scale drift; agent b
// covers 104..109 exactly, in its own frame; agent c covers 110..111 and was
// never placed in the common frame.
Pose2 own_a(double t) { return {1.01 * (t - 100.0), 0.0, 0.0}; }
Pose2 own_b(double t) { return kFrameB.inverse() * world(t); }

SwarmOutput make_output() {
  SwarmOutput out;
  SwarmAgentOutput a{"a", {}, Trajectory{}}, b{"b", {}, Trajectory{}}, c{"c", {}, std::nullopt};
  for (int i = 0; i <= 5; ++i) a.own.push_back({100.0 + i, own_a(100.0 + i)});
  a.joint = a.own;  // the first agent's frame is the common frame
  for (int i = 9; i >= 4; --i) {  // played backward
    b.own.push_back({100.0 + i, own_b(100.0 + i)});
    b.joint->push_back({100.0 + i, kFrameBEstimate * own_b(100.0 + i)});
  }
  for (int i = 10; i <= 11; ++i) c.own.push_back({100.0 + i, world(100.0 + i)});
  out.agents = {a, b, c};
  return out;
}

std::vector<Relation> make_relations() {
  std::vector<Relation> r;
  for (int i = 0; i < 9; ++i) {
    const double t = 100.0 + i;
    if (i == 4) {
      r.push_back({t + 1, t, Pose2(-1, 0, 0)});  // stated the other way round
    } else {
      r.push_back({t, t + 1, Pose2(1, 0, 0)});
    }
  }
  r.push_back({104, 106, Pose2(2, 0, 0)});   // t1 covered by a and b: only b's
  r.push_back({101, 107, Pose2(6, 0, 0)});   // cross a → b
  r.push_back({102, 108, Pose2(6, 0, 0)});   // cross a → b
  r.push_back({108, 102, Pose2(-6, 0, 0)});  // cross b → a
  r.push_back({103, 110, Pose2(7, 0, 0)});   // cross a → c: c has no joint pose
  r.push_back({103, 200, Pose2(97, 0, 0)});  // 200: nobody
  return r;
}

SwarmEncounterEntry encounter(const std::string& a, const std::string& b, double ta, double tb,
                              std::optional<Pose2> transform, bool accepted = true) {
  SwarmEncounterEntry e;
  e.a = a;
  e.b = b;
  e.a_log_time = ta;
  e.b_log_time = tb;
  e.a_pose = a == "a" ? own_a(ta) : own_b(ta);
  e.b_pose = b == "a" ? own_a(tb) : own_b(tb);
  e.transform = transform;
  e.accepted = accepted;
  return e;
}

TEST(SwarmEval, PerAgentScoresUseTheRelationsTheAgentCovers) {
  const SwarmEvaluation ev = evaluate_swarm(make_output(), make_relations());
  ASSERT_EQ(ev.agents.size(), 3u);
  EXPECT_EQ(ev.agents[0].relations_covered, 5u);  // 100-101 .. 104-105 (one stated backwards)
  ASSERT_TRUE(ev.agents[0].metrics);
  EXPECT_NEAR(ev.agents[0].metrics->trans_mean, 0.01, 1e-9);  // 1% of 1 m
  EXPECT_EQ(ev.agents[1].relations_covered, 6u);  // 104-105 .. 108-109, and 104-106
  ASSERT_TRUE(ev.agents[1].metrics);
  EXPECT_NEAR(ev.agents[1].metrics->trans_mean, 0.0, 1e-9);  // b's frame is rigid: relative motions exact
  EXPECT_EQ(ev.agents[2].relations_covered, 0u);
  EXPECT_FALSE(ev.agents[2].metrics);
  EXPECT_FALSE(ev.agents[2].joint);
}

TEST(SwarmEval, CrossAgentRelationsAreScoredOnTheJointTrajectories) {
  const SwarmEvaluation ev = evaluate_swarm(make_output(), make_relations());
  EXPECT_EQ(ev.cross_relations, 4u);
  EXPECT_EQ(ev.cross_without_joint, 1u);
  ASSERT_TRUE(ev.cross);
  ASSERT_EQ(ev.cross->used, 3u);
  // 101→107: a at 1.01, b at 7.1 in the joint frame: 6.09 for 6; 102→108: 6.08; 108→102: −6.08.
  EXPECT_NEAR(ev.cross->trans_errors[0], 0.09, 1e-9);
  EXPECT_NEAR(ev.cross->trans_errors[1], 0.08, 1e-9);
  EXPECT_NEAR(ev.cross->trans_errors[2], 0.08, 1e-9);
  ASSERT_EQ(ev.pairs.size(), 2u);
  EXPECT_EQ(ev.pairs[0].x, "a");
  EXPECT_EQ(ev.pairs[0].y, "b");
  EXPECT_EQ(ev.pairs[0].relations, 3u);
  EXPECT_EQ(ev.pairs[1].y, "c");
  EXPECT_EQ(ev.pairs[1].without_joint, 1u);
  EXPECT_FALSE(ev.pairs[1].metrics);
  // The frame fitted in hindsight removes the 10 cm the encounter put in:
  // what is left is a's 1% drift over the relations (a few mm).
  ASSERT_TRUE(ev.pairs[0].hindsight);
  EXPECT_EQ(ev.pairs[0].hindsight->used, 3u);
  EXPECT_LT(ev.pairs[0].hindsight->trans_mean, 0.02);
  EXPECT_FALSE(ev.pairs[1].hindsight_frame);  // one relation with c: no fit
  const nlohmann::json j = to_json(ev);
  EXPECT_LT(j["cross"]["pairs"][0]["hindsight_metrics"]["trans_mean"].get<double>(), 0.02);
  EXPECT_NE(format_swarm_evaluation(ev).find("best frame"), std::string::npos);
}

TEST(SwarmEval, EncounterTransformsAgainstRelationTruth) {
  SwarmOutput out = make_output();
  out.encounters = {
      encounter("a", "b", 104, 104, kFrameBEstimate),                    // same scan
      encounter("a", "b", 103, 107, kFrameBEstimate),                    // chain 103-104, 104-106, 106-107
      encounter("a", "b", 101, 107, kFrameBEstimate),                    // one relation
      encounter("a", "b", 101, 107, std::nullopt, false),                // rejected, no candidate
      encounter("a", "b", 104.5, 107, kFrameBEstimate),                  // 104.5 is no relation's
      encounter("b", "a", 107, 103, kFrameBEstimate.inverse()),          // the other way round
  };
  const SwarmEvaluation ev = evaluate_swarm(out, make_relations());
  ASSERT_EQ(ev.encounters.size(), 6u);
  // a at 4.04 (drift), b exactly at 4 with a 10 cm frame error: 0.06.
  ASSERT_TRUE(ev.encounters[0].scored());
  EXPECT_EQ(ev.encounters[0].truth->hops, 0u);
  EXPECT_NEAR(ev.encounters[0].trans_error, 0.06, 1e-9);
  ASSERT_TRUE(ev.encounters[1].scored());
  EXPECT_EQ(ev.encounters[1].truth->hops, 3u);
  EXPECT_NEAR(ev.encounters[1].truth->motion.x, 4.0, 1e-12);
  EXPECT_NEAR(ev.encounters[1].trans_error, 0.07, 1e-9);  // 7.1 − 3.03 = 4.07 for 4
  EXPECT_EQ(ev.encounters[2].truth->hops, 1u);
  EXPECT_NEAR(ev.encounters[2].trans_error, 0.09, 1e-9);
  EXPECT_NEAR(ev.encounters[2].rot_error_deg, 0.0, 1e-9);
  EXPECT_FALSE(ev.encounters[3].scored());
  // 104.5 is no relation's: checked at 104 (the nearest, first on a tie) with a's own pose there: 7.1 − 4.04.
  ASSERT_TRUE(ev.encounters[4].scored());
  EXPECT_TRUE(ev.encounters[4].bridged());
  EXPECT_EQ(ev.encounters[4].a_time, 104.0);
  EXPECT_EQ(ev.encounters[4].b_time, 107.0);
  EXPECT_EQ(ev.encounters[4].truth->hops, 2u);
  EXPECT_NEAR(ev.encounters[4].trans_error, 0.06, 1e-9);
  EXPECT_FALSE(ev.encounters[0].bridged());
  ASSERT_TRUE(ev.encounters[5].scored());  // chain walked against the relations' direction
  EXPECT_NEAR(ev.encounters[5].truth->motion.x, -4.0, 1e-12);
  EXPECT_NEAR(ev.encounters[5].trans_error, 0.07, 1e-9);

  const nlohmann::json j = to_json(ev);
  EXPECT_EQ(j.at("encounter_summary").at("accepted").get<int>(), 5);
  EXPECT_EQ(j.at("encounter_summary").at("scored").get<int>(), 5);
  EXPECT_NEAR(j.at("encounter_summary").at("trans_max").get<double>(), 0.09, 1e-9);
  EXPECT_NEAR(j.at("encounter_summary").at("trans_mean").get<double>(), (0.06 + 0.07 + 0.09 + 0.06 + 0.07) / 5, 1e-9);
  EXPECT_EQ(j.at("encounters")[1].at("truth"), "chain of 3");
  EXPECT_TRUE(j.at("encounters")[3].at("trans_error").is_null());
  EXPECT_TRUE(j.at("encounters")[4].at("bridged").get<bool>());
  const std::string table = format_swarm_evaluation(ev);
  EXPECT_NE(table.find("0.0900"), std::string::npos) << table;
  EXPECT_NE(table.find("0.50"), std::string::npos) << table;  // the shift of encounter 4

  // Without the bridge, or with one too short, 104.5 has no truth.
  for (const double bridge : {0.0, 0.4}) {
    const SwarmEvaluation strict = evaluate_swarm(out, make_relations(), {0.001, 4, bridge});
    EXPECT_FALSE(strict.encounters[4].truth) << bridge;
    EXPECT_NE(format_swarm_evaluation(strict).find("no relation"), std::string::npos);
  }
}

TEST(SwarmEval, BadOptionsAreConfigErrors) {
  EXPECT_THROW(evaluate_swarm(make_output(), make_relations(), {-1.0, 4, 2.0}), ConfigError);
  EXPECT_THROW(evaluate_swarm(make_output(), make_relations(), {0.001, 4, -2.0}), ConfigError);
}

TEST(SwarmEval, ChainsLongerThanTheLimitAreNoTruth) {
  const RelationGraph graph(make_relations(), 0.001);
  EXPECT_TRUE(graph.motion(103, 107, 3));
  EXPECT_FALSE(graph.motion(103, 107, 2));
  const auto direct = graph.motion(101.0005, 107, 1);  // within max_time_diff of the endpoint
  ASSERT_TRUE(direct);
  EXPECT_NEAR(direct->motion.x, 6.0, 1e-12);
  EXPECT_FALSE(graph.motion(101.002, 107, 4));
}

// ------------------------------------------------------------ files

fs::path write_output(const std::string& name, const std::string& encounters_json) {
  const fs::path dir = test::fresh_dir("swarm_eval/" + name);
  const SwarmOutput out = make_output();
  for (const SwarmAgentOutput& a : out.agents) {
    fs::create_directories(dir / "agents" / a.name);
    write_tum(dir / "agents" / a.name / "trajectory.tum", a.own);
    if (a.joint) {
      fs::create_directories(dir / "joint");
      write_tum(dir / "joint" / (a.name + ".tum"), *a.joint);
    }
  }
  if (!encounters_json.empty()) test::write_text(dir / "encounters.json", encounters_json);
  return dir;
}

const char* kGoodEntry =
    R"({"time": 3.5, "agents": ["a", "b"], "log_times": [101, 107], "poses": [[1.01, 0, 0], [POSE_B]],
        "transform": [TRANSFORM], "accepted": true, "reason": "", "match_ms": 12.5, "merge_ms": 3, "bytes": 1000,
        "true_transform": [0, 0, 0]})";

std::string good_entry() {
  std::string s = kGoodEntry;
  const Pose2 b = own_b(107);
  s.replace(s.find("POSE_B"), 6, std::to_string(b.x) + ", " + std::to_string(b.y) + ", " + std::to_string(b.theta));
  const Pose2& t = kFrameBEstimate;
  s.replace(s.find("TRANSFORM"), 9, std::to_string(t.x) + ", " + std::to_string(t.y) + ", " + std::to_string(t.theta));
  return s;
}

TEST(SwarmEval, ReadsAnOutputFolder) {
  const fs::path dir = write_output("folder", R"({"encounters": [)" + good_entry() + "]}");
  const SwarmOutput out = read_swarm_output(dir);
  ASSERT_EQ(out.agents.size(), 3u);
  EXPECT_EQ(out.agents[1].name, "b");
  EXPECT_EQ(out.agents[1].own.front().timestamp, 109.0);  // play order kept
  EXPECT_TRUE(out.agents[1].joint);
  EXPECT_FALSE(out.agents[2].joint);
  ASSERT_EQ(out.encounters.size(), 1u);
  EXPECT_EQ(out.encounters[0].match_ms, 12.5);
  const SwarmEvaluation ev = evaluate_swarm(out, make_relations());
  ASSERT_TRUE(ev.encounters[0].scored());
  EXPECT_NEAR(ev.encounters[0].trans_error, 0.09, 1e-5);  // the file holds 6 decimals
}

TEST(SwarmEval, NoEncountersFileMeansNoEncounters) {
  EXPECT_TRUE(read_swarm_output(write_output("none", "")).encounters.empty());
}

TEST(SwarmEval, MalformedEncountersNameTheFileEntryAndField) {
  struct Case {
    std::string from, to, field;
  };
  const std::vector<Case> cases = {
      {R"("time": 3.5,)", "", "'time'"},
      {R"("time": 3.5)", R"("time": "soon")", "'time'"},
      {R"("agents": ["a", "b"])", R"("agents": ["a"])", "'agents'"},
      {R"("agents": ["a", "b"])", R"("agents": ["a", 2])", "'agents'"},
      {R"("log_times": [101, 107])", R"("log_times": [101, null])", "'log_times'"},
      {R"("poses": [[1.01, 0, 0], )", R"("poses": [[1.01, 0], )", "'poses'"},
      {R"("accepted": true)", R"("accepted": "yes")", "'accepted'"},
      {R"("transform": [)", R"("transform": null, "x": [)", "'transform'"},
      {R"("match_ms": 12.5)", R"("match_ms": "fast")", "'match_ms'"},
  };
  for (const Case& c : cases) {
    std::string entry = good_entry();
    ASSERT_NE(entry.find(c.from), std::string::npos) << c.from;
    entry.replace(entry.find(c.from), c.from.size(), c.to);
    const fs::path dir = write_output("malformed", R"({"encounters": [)" + good_entry() + ", " + entry + "]}");
    try {
      read_swarm_output(dir);
      ADD_FAILURE() << c.field << ": accepted " << entry;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find((dir / "encounters.json").string()), std::string::npos) << message;
      EXPECT_NE(message.find("encounters[1]"), std::string::npos) << message;
      EXPECT_NE(message.find("field " + c.field), std::string::npos) << message;
    }
  }
}

TEST(SwarmEval, BrokenFilesAreInputErrors) {
  const auto message_of = [](const fs::path& dir) {
    try {
      read_swarm_output(dir);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message_of(write_output("bad_json", "{\"encounters\": [")).find("invalid JSON"), std::string::npos);
  EXPECT_NE(message_of(write_output("bad_root", "[]")).find("field 'encounters'"), std::string::npos);
  std::string stranger = good_entry();
  stranger.replace(stranger.find("\"b\"]"), 3, "\"z\"");
  EXPECT_NE(message_of(write_output("stranger", R"({"encounters": [)" + stranger + "]}")).find("no agent 'z'"),
            std::string::npos);
  EXPECT_NE(message_of(test::fresh_dir("swarm_eval/empty")).find("no agents/ folder"), std::string::npos);
}

// Loop closing after the encounter moved b's trajectory there by 1 m; the
// transform was found against b's map as it stood. Bridged to a relation's
// timestamp, the encounter is checked against b's pose as it stood (moved
// only by b's own motion in between), as an encounter at a relation's
// timestamp is.
TEST(SwarmEval, ABridgedEncounterIsCheckedAgainstThePosesAsTheyStood) {
  SwarmOutput out = make_output();
  Trajectory& b = out.agents[1].own;
  b.push_back({106.5, own_b(106.5)});  // b's scan at the encounter, between two relations' timestamps
  for (StampedPose& p : b) p.pose = Pose2(0.0, 1.0, 0.0) * p.pose;  // moved by a later closure
  out.encounters = {encounter("a", "b", 104, 106.5, kFrameBEstimate)};  // b's pose as it stood
  const SwarmEvaluation ev = evaluate_swarm(out, make_relations());
  ASSERT_TRUE(ev.encounters[0].scored());
  EXPECT_TRUE(ev.encounters[0].bridged());
  EXPECT_EQ(ev.encounters[0].b_time, 106.0);
  // a at 4.04 (drift), b at 6 with the frame's 10 cm: 2.06 for 2 (1.02 m off from b's final pose).
  EXPECT_NEAR(ev.encounters[0].trans_error, 0.06, 1e-9);
}

}  // namespace
}  // namespace dsswarm
