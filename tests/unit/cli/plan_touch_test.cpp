#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "cli_run.hpp"
#include "temp_folder.hpp"
#include "test_config.hpp"

// --plan --touch POCKETS: the touch path, its touches as if they touched
// where expected, checked against the keep-out with the probe's length.

namespace fatc {
namespace {

const auto& run = test::run_cli;

class PlanTouch : public test::TempFolder {
 protected:
  std::string file(const std::string& name, const std::string& text) {
    const std::string path = folder_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }
  /// The sample config, T9 a probe, pockets found by their bores.
  std::string config() {
    return file("config.json", test::sample_config_with(R"({
      "tools": {"9": {"kind": "probe"}},
      "rack_touch": {"feature": "bore", "stylus_radius": 1.5, "bore_diameter": 30.0,
                     "top": {"x": 0, "y": -20}, "pocket_above_top": 10.0, "depth": 5.0,
                     "datum": {"pocket": 1}}})"));
  }
};

TEST_F(PlanTouch, shouldPrintTheTouchPathAndWhereItFindsThePockets) {
  const std::string table = file("tool.tbl", "T9 P9 Z50\n");
  const test::CliRun r =
      run({"--plan", "--config", config(), "--touch", "3,5", "--tool-table", table});
  EXPECT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_EQ(r.out.rfind("touch pocket 3, pocket 5 with T9 in the spindle, 50.0000 mm long, "
                        "rack_touch.feature \"bore\"\n",
                        0),
            0u)
      << r.out;
  // The top face of pocket 3 expected at -90: the nose 50 above, from 3 above it.
  EXPECT_NE(r.out.find("probe      Z=-45.000 F25"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pocket 3, top face (seek)"), std::string::npos);
  // The wall +X of pocket 3: 13.5 from the centre, the limit 5 beyond.
  EXPECT_NE(r.out.find("probe      X=168.500 F25"), std::string::npos) << r.out;
  // From wall to wall inside the bore, straight across.
  EXPECT_NE(r.out.find("feed       X=150.000 Y=20.000 F500               across to the start "
                       "of pocket 3, wall -X"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("  pocket 3   X 150.000 → 150.000 (+0.000)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  pocket 5   X 250.000 → 250.000 (+0.000)"), std::string::npos) << r.out;
}

TEST_F(PlanTouch, shouldCheckTheMovesWithTheProbesLength) {
  // 70 long, the probe's tip passes 15 below the holders' tops at safe Z (-5 over -60).
  const std::string table = file("tool.tbl", "T9 P9 Z70\n");
  const test::CliRun r =
      run({"--plan", "--config", config(), "--touch", "3,5", "--tool-table", table});
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("  touch, step 28 (rapid to over pocket 5, top face): carries T9 (length "
                       "70.0000 mm) with its tip 15.0000 mm below the top of the holder at pocket 3"),
            std::string::npos)
      << r.out;
}

TEST_F(PlanTouch, shouldTouchTheDatumOrEveryPocket) {
  const std::string table = file("tool.tbl", "T9 P9 Z50\n");
  const test::CliRun datum =
      run({"--plan", "--config", config(), "--touch", "datum", "--tool-table", table});
  EXPECT_EQ(datum.code, 0) << datum.out;
  EXPECT_NE(datum.out.find("touch the rack datum (pocket 1) with T9"), std::string::npos);
  const test::CliRun all =
      run({"--plan", "--config", config(), "--touch", "all", "--tool-table", table});
  EXPECT_NE(all.out.find("  pocket 6   "), std::string::npos) << all.out;
}

TEST_F(PlanTouch, shouldRefuseWhatItCannotTouch) {
  const std::string touching = config();
  EXPECT_EQ(run({"--plan", "--config", touching, "--touch", "9"}).out,
            "--touch: there is no pocket 9 in config.json\n");
  EXPECT_EQ(run({"--plan", "--config", touching, "--touch", "3", "--from", "2"}).out,
            "--plan --touch: T2 is not a probe (tools.2.kind): the touches need a 3D probe in "
            "the spindle\n");
  const test::CliRun plain =
      run({"--plan", "--config", file("plain.json", test::kValidConfig), "--touch", "3"});
  EXPECT_EQ(plain.code, 1);
  EXPECT_EQ(plain.out, "--plan --touch: config.json has no rack_touch: nothing is found by touch\n");
  const test::CliRun both = run({"--plan", "--config", touching, "--touch", "3", "--to", "2"});
  EXPECT_EQ(both.code, 2);
  EXPECT_EQ(both.err,
            "--plan: --touch POCKETS plans the touch path, --to B a change: give one of them");
  for (const char* bad : {"", "0", "3,3", "3,", "x", "All"}) {
    const test::CliRun r = run({"--plan", "--config", touching, "--touch", bad});
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_EQ(r.err.rfind("--touch: expected all, datum or pocket numbers like 3,5, got ", 0), 0u)
        << r.err;
  }
}

}  // namespace
}  // namespace fatc
