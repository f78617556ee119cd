// freshness.hpp: the stale-telemetry rule (docs/runtime.md, "Stale telemetry"), on a fake
// clock: the bound (declared, else 3 periods of the rate with a 1000 ms floor, else none),
// samples older than it refused, a source silent past it said once, back said once, and the
// words the Python runtime uses. K10's generated tables give the derived bounds.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include <rapid_runtime/freshness.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;

namespace {

constexpr std::int64_t T0 = 1'700'000'000'000'000;  // microseconds since the epoch
constexpr std::int64_t MS = 1000;

struct FakeClock {
    std::int64_t now = T0;
    Freshness::Clock clock() {
        return [this] { return now; };
    }
};

TelemetrySpec spec(const std::string& kind, std::optional<double> rate, double declared = 0) {
    TelemetrySpec e;
    e.kind = kind;
    e.topics = {{"config", "rapid_" + kind + "_config", ""}, {"sample", "rapid_" + kind + "_sample", ""}};
    e.rate = rate;
    e.stale_after_ms = declared;
    return e;
}

}  // namespace

TEST(Freshness, BoundDeclaredElseThreePeriodsOfTheRateAtLeastOneSecond) {
    EXPECT_EQ(stale_after_ms(spec("position", 10.0)), 1000.0);    // 300 ms, floored
    EXPECT_EQ(stale_after_ms(spec("position", 1.0)), 3000.0);
    EXPECT_EQ(stale_after_ms(spec("joint", 0.5)), 6000.0);
    EXPECT_EQ(stale_after_ms(spec("agent", 2.0)), 1500.0);
    EXPECT_EQ(stale_after_ms(spec("image", 10.0, 250)), 250.0);   // declared wins, even under the floor
    EXPECT_EQ(stale_after_ms(spec("position", std::nullopt, 1500)), 1500.0);
    EXPECT_EQ(stale_after_ms(spec("position", std::nullopt)), std::nullopt);  // on change: not watched
    EXPECT_EQ(stale_after_ms(spec("text", 1.0, 500)), std::nullopt);        // text, custom: never
    EXPECT_EQ(stale_after_ms(spec("custom", 1.0, 500)), std::nullopt);
}

TEST(Freshness, K10sGeneratedTablesDeriveTheirBounds) {
    const Tables& t = k10_tables();
    ASSERT_NE(t.telemetry_of("position"), nullptr);
    EXPECT_EQ(t.telemetry_of("position")->stale_after_ms, 0.0);  // not declared: derived
    EXPECT_EQ(stale_after_ms(*t.telemetry_of("position")), 3000.0);  // 1 Hz
    EXPECT_EQ(stale_after_ms(*t.telemetry_of("agent")), 1000.0);     // 4 Hz: 750 ms, floored
    EXPECT_EQ(stale_name(*t.telemetry_of("agent")), "rapid_agent_state");
    EXPECT_EQ(stale_name(*t.telemetry_of("position")), "rapid_position_sample");
    EXPECT_EQ(stale_after_ms(*t.telemetry_of("image", 0)), std::nullopt);  // panCamLeft: no rate
    EXPECT_EQ(stale_after_ms(*t.telemetry_of("image", 2)), 6000.0);       // hazCam: 0.5 Hz
    EXPECT_EQ(stale_after_ms(*t.telemetry_of("text")), std::nullopt);
}

TEST(Freshness, TheWordsAreThePythonRuntimes) {
    EXPECT_EQ(silent_text("rapid_position_sample", 3.25), "rapid_position_sample source silent for 3.2 s: samples stopped");
    EXPECT_EQ(silent_text("rapid_agent_state", 12.0), "rapid_agent_state source silent for 12.0 s: samples stopped");
    EXPECT_EQ(back_text("rapid_position_sample"), "rapid_position_sample source back");
}

TEST(Freshness, OldSamplesAreRefusedCurrentOnesPass) {
    FakeClock c;
    Freshness f(c.clock());
    f.watch("pos", 1000);
    EXPECT_TRUE(f.offer("pos", T0).ok);
    EXPECT_TRUE(f.offer("pos", T0 - 1000 * MS).ok);        // exactly the bound: still current
    EXPECT_FALSE(f.offer("pos", T0 - 1000 * MS - 1).ok);   // a microsecond older: refused
    c.now += 5000 * MS;
    EXPECT_FALSE(f.offer("pos", T0).ok);  // the same stamp again, 5 s later (a republished last value)
    EXPECT_TRUE(f.offer("other", T0 - 3600 * 1000 * MS).ok);  // not watched: always
}

TEST(Freshness, SilentPastTheBoundIsSaidOnceAndBackOnce) {
    FakeClock c;
    Freshness f(c.clock());
    f.watch("pos", 1000);
    f.watch("joints", 3000);
    EXPECT_TRUE(f.check().empty());  // no sample yet: not silent
    EXPECT_FALSE(f.offer("pos", c.now).back);
    EXPECT_FALSE(f.offer("joints", c.now).back);
    c.now += 1000 * MS;
    EXPECT_TRUE(f.check().empty());  // at the bound: not yet
    c.now += 500 * MS;
    auto silent = f.check();
    ASSERT_EQ(silent.size(), 1u);
    EXPECT_EQ(silent[0].first, "pos");
    EXPECT_DOUBLE_EQ(silent[0].second, 1.5);
    EXPECT_EQ(f.silent_names(), std::vector<std::string>{"pos"});
    c.now += 10000 * MS;
    silent = f.check();  // pos said already; joints now
    ASSERT_EQ(silent.size(), 1u);
    EXPECT_EQ(silent[0].first, "joints");
    EXPECT_TRUE(f.check().empty());  // once
    EXPECT_EQ(f.silent_names(), (std::vector<std::string>{"joints", "pos"}));

    EXPECT_FALSE(f.offer("pos", c.now - 2000 * MS).ok);  // an old sample does not bring it back
    EXPECT_EQ(f.silent_names().size(), 2u);
    auto back = f.offer("pos", c.now);
    EXPECT_TRUE(back.ok);
    EXPECT_TRUE(back.back);
    EXPECT_FALSE(f.offer("pos", c.now).back);  // back once
    EXPECT_EQ(f.silent_names(), std::vector<std::string>{"joints"});
    EXPECT_TRUE(f.check().empty());

    c.now += 1001 * MS;  // silent again: said again
    silent = f.check();
    ASSERT_EQ(silent.size(), 1u);
    EXPECT_EQ(silent[0].first, "pos");
}

TEST(Freshness, SmallestBound) {
    Freshness f;
    EXPECT_TRUE(f.empty());
    EXPECT_EQ(f.smallest_bound_ms(), 0.0);
    f.watch("a", 3000);
    f.watch("b", 1500);
    EXPECT_FALSE(f.empty());
    EXPECT_EQ(f.smallest_bound_ms(), 1500.0);
    EXPECT_TRUE(f.watched("a"));
    EXPECT_FALSE(f.watched("c"));
}
