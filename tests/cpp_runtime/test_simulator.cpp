// The simulated robot's state and command behaviour (runtime/cpp simulator.hpp; no DDS) on
// K10's generated tables and on small tables with joints, and the synthetic pictures
// (images.hpp). With RAPID_IMAGES_OUT set, the pictures are written there for the pytest
// side to decode (tests/cpp_runtime/test_cpp_runtime.py).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <rapid_runtime/command.hpp>
#include <rapid_runtime/images.hpp>
#include <rapid_runtime/simulator.hpp>

#include "k10_tables.hpp"

using namespace rapid_runtime;

namespace {

struct Call {
    std::shared_ptr<Cmd> cmd = std::make_shared<Cmd>();
    std::unique_ptr<CommandContext> ctx;
    Call(const Tables& t, const std::string& sub, const std::string& name, std::vector<Value> args) {
        cmd->subsystem = sub;
        cmd->name = name;
        cmd->args = std::move(args);
        ctx = std::make_unique<CommandContext>(cmd, t.command(sub, name), [](const std::string&) {});
    }
};

Result execute(Simulator& sim, Call& r) {
    try {
        return sim.execute(*r.ctx);
    } catch (const Cancelled&) {
        return Result::canceled();
    }
}

Tables arm_tables() {
    Tables t;
    t.name = "Arm";
    t.subsystems = {{"Arm", "Arm"}};
    Param a{"shoulder", DataType::Float, "rad", -1.0, 1.0, {}, std::nullopt, ""};
    Param b{"elbow", DataType::Float, "rad", -2.0, 2.0, {}, std::nullopt, ""};
    t.types = {{"Arm", {{"setJoints", {a, b}, true, false, false, ""}}}};
    TelemetrySpec joints;
    joints.kind = "joint";
    joints.subsystem = "Arm";
    joints.joints = {{"Arm/shoulder", "pitch", "rad", -1.0, 0.5}, {"Arm/elbow", "pitch", "rad", std::nullopt, 3.0}};
    TelemetrySpec agent;
    agent.kind = "agent";
    agent.values = {Param{"batteryCharge", DataType::Float, "%", 0.0, 100.0, {}, std::nullopt, ""},
                    Param{"mode", DataType::String, "", std::nullopt, std::nullopt,
                          {Value(std::string("idle")), Value(std::string("busy"))}, std::nullopt, ""},
                    Param{"limit", DataType::Int, "", 3.0, 9.0, {}, std::nullopt, ""}};
    t.telemetry = {joints, agent};
    return t;
}

}  // namespace

TEST(Simulator, DrivesToTheGoalAndCounts) {
    Simulator sim(k10_tables(), 50.0);
    Call r(k10_tables(), "Mobility", "simpleMove", {Value(std::string("site")), Value(Vec3d{2.0, 1.0, 0.5})});
    auto done = execute(sim, r);
    EXPECT_EQ(done.completion, Completion::Ok);
    EXPECT_EQ(done.message, "arrived at 2.00, 1.00");
    auto body = sim.body();
    EXPECT_NEAR(body.xyz[0], 2.0, 1e-3);
    EXPECT_NEAR(body.xyz[1], 1.0, 1e-3);
    EXPECT_NEAR(body.heading, 0.5, 1e-3);
    EXPECT_NEAR(body.odometer, std::hypot(2.0, 1.0), 1e-2);
    EXPECT_EQ(body.velocity[0], 0.0);
    Call nan(k10_tables(), "Mobility", "simpleMove", {Value(std::string("site")), Value(Vec3d{NAN, 0.0, 0.0})});
    EXPECT_EQ(execute(sim, nan).completion, Completion::ExecFailed);
}

TEST(Simulator, AMoveIsCanceledWhileItDrives) {
    Simulator sim(k10_tables(), 1.0);
    Call r(k10_tables(), "Mobility", "move",
          {Value(std::string("site")), Value(Vec3d{100.0, 0.0, 0.0}), Value(Vec3d{-1, -1, -1})});
    std::thread cancel([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(150));
        r.ctx->cancel();
    });
    EXPECT_EQ(execute(sim, r).completion, Completion::Canceled);
    cancel.join();
    auto body = sim.body();
    EXPECT_GT(body.xyz[0], 0.0);
    EXPECT_LT(body.xyz[0], 1.0);
    EXPECT_EQ(body.velocity[0], 0.0);
}

TEST(Simulator, PicturesNeedTheCamerasAndPickThemByMode) {
    Simulator sim(k10_tables(), 100.0);
    Call r(k10_tables(), "PanCam", "takePicture", {Value(std::string("left")), Value(0.0f)});
    EXPECT_EQ(execute(sim, r).completion, Completion::ExecFailed);  // no camera hook yet
    std::vector<std::size_t> taken;
    sim.on_picture([&](std::size_t i) { taken.push_back(i); });
    auto ok = execute(sim, r);
    EXPECT_EQ(ok.message, "1 picture(s) taken: PanCamLeft (simulated)");
    Call both(k10_tables(), "PanCam", "takePanorama", {Value(0.0f), Value(1.0f), Value(0.0f), Value(std::int32_t{4})});
    execute(sim, both);
    EXPECT_EQ(taken, (std::vector<std::size_t>{0, 0, 1}));
    EXPECT_TRUE(sim.has_picture_command("PanCam"));
    EXPECT_FALSE(sim.has_picture_command("HazCams"));
    Call other(k10_tables(), "K10Native", "nativeCommand", {Value(std::string("ls"))});
    EXPECT_EQ(execute(sim, other).message, "done (simulated)");
}

TEST(Simulator, JointsMoveToClampedSetpointsAndTheBatteryDrains) {
    Tables t = arm_tables();
    Simulator sim(t, 100.0);
    EXPECT_EQ(sim.joints(0), (std::vector<double>{0.0, 0.0}));
    Call r(t, "Arm", "setJoints", {Value(0.9f), Value(-1.5f)});
    EXPECT_EQ(execute(sim, r).message, "2 joint(s) at setpoint");
    auto j = sim.joints(0);
    EXPECT_NEAR(j[0], 0.5, 1e-6);  // the joint's limit, not the command's range
    EXPECT_NEAR(j[1], -1.5, 1e-6);
    auto agent = sim.agent();
    EXPECT_EQ(std::get<float>(agent["batteryCharge"]), 100.0f);
    EXPECT_EQ(std::get<std::string>(agent["mode"]), "idle");
    EXPECT_EQ(std::get<std::int32_t>(agent["limit"]), 3);
    sim.advance(10.0);  // 100x: 20 %
    EXPECT_NEAR(std::get<float>(sim.agent()["batteryCharge"]), 80.0f, 1e-3);
}

TEST(Images, EveryFormatSaysItsSizeAndKind) {
    const char* out = std::getenv("RAPID_IMAGES_OUT");
    struct Case {
        const char* mime;
        int w, h;
        bool grey;
        const char* file;
    };
    const Case cases[] = {{"image/png", 640, 480, false, "rgb.png"},   {"image/png", 37, 13, true, "grey.png"},
                          {"image/jpeg", 1360, 1024, false, "rgb.jpg"}, {"image/jpeg", 33, 17, true, "grey.jpg"},
                          {"image/bmp", 21, 9, false, "rgb.bmp"},       {"image/x-portable-graymap", 5, 3, true, "g.pgm"}};
    for (const auto& c : cases) {
        auto data = synthetic_image(c.mime, c.w, c.h, 0.7, 5, c.grey);
        ImageInfo info;
        ASSERT_TRUE(describe_image(data, info)) << c.file;
        EXPECT_EQ(info.mime, c.mime);
        EXPECT_EQ(info.width, c.w);
        EXPECT_EQ(info.height, c.h);
        EXPECT_LT(data.size(), 200000u) << c.file;
        if (out != nullptr) {
            std::ofstream f(std::string(out) + "/" + c.file, std::ios::binary);
            f.write(reinterpret_cast<const char*>(data.data()), static_cast<std::streamsize>(data.size()));
        }
    }
    EXPECT_THROW(synthetic_image("image/tiff", 4, 4), ImageError);
    EXPECT_THROW(synthetic_image("image/png", 0, 4), ImageError);
}
