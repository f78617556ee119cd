// The generated handler glue of K10 (bridge/dispatch.cpp and handlers.hpp of `rapidgen
// generate specs/assets/k10.yaml --lang cpp`): a command's arguments reach its typed method
// in order and type, a type without a handler answers "not implemented", and the hooks run.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <rapid_runtime/command.hpp>
#include <rapid_runtime/handlers.hpp>

#include "handlers.hpp"
#include "k10_tables.hpp"

using namespace rapid_runtime;
namespace k10 = rapid_k10red::bridge;

namespace {

class GlueCamera final : public k10::PanTiltCameraHandler {
public:
    explicit GlueCamera(std::vector<std::string>& log) : log_(log) {}
    Result pointCamera(CommandContext& ctx, float pan, float tilt) override {
        log_.push_back(ctx.subsystem() + " point " + std::to_string(pan) + " " + std::to_string(tilt));
        return Result::ok("pointed");
    }
    Result takePicture(CommandContext&, const std::string& mode, float exposure) override {
        log_.push_back("picture " + mode + " " + std::to_string(exposure));
        return Result::failed("lens cap on");
    }
    Result takePanorama(CommandContext&, float a, float b, float tilt, std::int32_t tiles) override {
        log_.push_back("panorama " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(tilt) + " " +
                       std::to_string(tiles));
        return Result::ok();
    }

private:
    std::vector<std::string>& log_;
};

class Mobility final : public k10::MobilityHandler {
public:
    explicit Mobility(std::vector<std::string>& log) : log_(log) {}
    Result stopAllMotion(CommandContext&) override { return Result::ok("stopped"); }
    Result simpleMove(CommandContext&, const std::string& frame, const Vec3d& xyt) override {
        log_.push_back("simpleMove " + frame + " " + std::to_string(xyt[0]) + " " + std::to_string(xyt[2]));
        return Result::ok();
    }
    Result move(CommandContext&, const std::string&, const Vec3d&, const Vec3d&) override { return Result::ok(); }
    Result move6DOF(CommandContext&, const std::string&, const Vec3d&, const Mat33f& rot) override {
        log_.push_back("move6DOF " + std::to_string(rot[8]));
        return Result::ok();
    }

private:
    std::vector<std::string>& log_;
};

Result run(k10::Dispatch& d, const std::string& sub, const std::string& name, std::vector<Value> args) {
    auto cmd = std::make_shared<Cmd>();
    cmd->cmd_id = "c1";
    cmd->subsystem = sub;
    cmd->name = name;
    cmd->args = std::move(args);
    CommandRef ref = k10_tables().command(sub, name);
    EXPECT_TRUE(ref) << sub << "/" << name;
    CommandContext ctx(cmd, ref, [](const std::string&) {});
    return d.execute(ctx);
}

}  // namespace

TEST(Glue, ArgumentsReachTheTypedMethodsInOrder) {
    std::vector<std::string> log;
    k10::HandlerSet set;
    set.pan_tilt_camera = std::make_unique<GlueCamera>(log);
    set.mobility = std::make_unique<Mobility>(log);
    k10::Dispatch d(std::move(set));
    EXPECT_EQ(run(d, "PanCam", "pointCamera", {Value(0.5f), Value(-0.25f)}).message, "pointed");
    auto failed = run(d, "PanCam", "takePicture", {Value(std::string("left")), Value(12.0f)});
    EXPECT_EQ(failed.completion, Completion::ExecFailed);
    EXPECT_EQ(failed.message, "lens cap on");
    run(d, "PanCam", "takePanorama", {Value(-1.0f), Value(1.0f), Value(0.5f), Value(std::int32_t{12})});
    run(d, "Mobility", "simpleMove", {Value(std::string("site")), Value(Vec3d{3.0, 4.0, 1.5})});
    run(d, "Mobility", "move6DOF",
        {Value(std::string("site")), Value(Vec3d{}), Value(Mat33f{1, 0, 0, 0, 1, 0, 0, 0, 7})});
    EXPECT_EQ(log, (std::vector<std::string>{"PanCam point 0.500000 -0.250000", "picture left 12.000000",
                                             "panorama -1.000000 1.000000 0.500000 12",
                                             "simpleMove site 3.000000 1.500000", "move6DOF 7.000000"}));
}

TEST(Glue, ATypeWithoutHandlerAnswersNotImplemented) {
    k10::Dispatch d(k10::HandlerSet{});
    auto r = run(d, "K10Native", "nativeCommand", {Value(std::string("ls"))});
    EXPECT_EQ(r.completion, Completion::ExecFailed);
    EXPECT_EQ(r.message, "not implemented");
    r = run(d, "Queue", "loadMacro", {Value(std::string("m"))});
    EXPECT_EQ(r.message, "not implemented");
}

TEST(Glue, BuiltInsHaveNoMethodsAndHooksRun) {
    // Admin and AccessControl are the runtime's: the generated set has no member for them
    // (this compiles only while HandlerSet holds exactly these four handler types).
    k10::HandlerSet set{nullptr, nullptr, nullptr, nullptr, {}, {}};
    int started = 0, stopped = 0;
    set.on_start = [&](rapid_runtime::dds::Bridge&) { ++started; };
    set.on_stop = [&] { ++stopped; };
    k10::Dispatch d(std::move(set));
    d.on_stop();
    EXPECT_EQ(stopped, 1);
    EXPECT_EQ(started, 0);
}

TEST(Glue, TablesCarryTheDescriptor) {
    const auto& t = k10_tables();
    EXPECT_EQ(t.name, "K10Red");
    auto ref = t.command("PanCam", "takePicture");
    ASSERT_TRUE(ref);
    ASSERT_EQ(ref.spec->params.size(), 2u);
    EXPECT_EQ(ref.spec->params[0].allowed.size(), 3u);
    EXPECT_EQ(std::get<std::string>(*ref.spec->params[0].default_value), "stereo");
    EXPECT_EQ(ref.spec->params[1].unit, "ms");
    EXPECT_EQ(*ref.spec->params[1].max, 2000.0);
    EXPECT_FALSE(ref.spec->standard);
    EXPECT_TRUE(t.command("Mobility", "simpleMove").spec->abortable);
    ASSERT_TRUE(t.access.has_value());
    EXPECT_FALSE(t.access->allow_by_default);
    ASSERT_EQ(t.count_of("image"), 3u);
    const auto* haz = t.telemetry_of("image", 2);
    EXPECT_EQ(haz->mime, "image/png");
    EXPECT_EQ(haz->width, 640);
    EXPECT_EQ(*haz->rate, 0.5);
    EXPECT_EQ(haz->topic("sample")->topic, "rapid_imagesensor_sample-hazCam");
    const auto* agent = t.telemetry_of("agent");
    EXPECT_EQ(agent->topic("state")->qos, "RapidSampleQos");
    const auto* custom = t.telemetry_of("custom");
    ASSERT_EQ(custom->types.size(), 2u);
    EXPECT_EQ(custom->types[1].second, "rapid::ext::arc::GpsSample");
}
