// A plausible simulated robot behind the handlers (`--simulate`; the C++ twin of
// runtime/rapid_runtime/simulate.py): a body that drives toward a commanded point, joints
// that move toward setpoints, a battery that drains. Every command of the dictionary gets
// an answer: Mobility moves take the time the drive takes (and can be canceled or
// preempted), a command setting numbers on a subsystem with joints moves them, a picture
// command on a camera's subsystem has its pictures taken (the DDS side publishes them), and
// anything else completes after a short pause. What it publishes is the DDS layer's
// (dds/simulate.hpp): this part holds the state and the command behaviour, no DDS.
#ifndef RAPID_RUNTIME_SIMULATOR_HPP
#define RAPID_RUNTIME_SIMULATOR_HPP

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "handlers.hpp"
#include "tables.hpp"

namespace rapid_runtime {

namespace sim {
inline constexpr double DRIVE_SPEED = 0.5;  // m/s
inline constexpr double TURN_SPEED = 0.5;  // rad/s
inline constexpr double JOINT_SPEED = 1.0;  // rad/s
inline constexpr double DRAIN = 0.02;  // battery %/s
inline constexpr double TICK = 0.05;  // s
// Telemetry without a declared rate (extension samples, cameras no command triggers) goes
// out every IDLE_PERIOD seconds; agent, position and joint samples at 1 Hz.
inline constexpr double IDLE_PERIOD = 5.0;
}  // namespace sim

// Whether a command name says it takes pictures (picture, image, photo, snap, capture,
// panorama, acquire, shoot; any case).
bool picture_command(const std::string& name);

class Simulator : public Handlers {
public:
    struct Body {
        std::array<double, 3> xyz{};  // site frame, m
        double heading = 0.0;  // rad
        std::array<double, 3> velocity{};  // m/s
        double odometer = 0.0;  // m
    };

    // speed: simulated time runs this many times faster (at least 0.001).
    explicit Simulator(const Tables& tables, double speed = 1.0);

    Result execute(CommandContext& ctx) override;

    Body body() const;
    // Positions of the joints of a joint entry (index among joint entries), in its order.
    std::vector<double> joints(std::size_t joint_entry) const;
    // Agent values by key (every agent entry's keys), as declared types.
    std::map<std::string, Value> agent() const;
    // Seconds pass: the battery drains, stream-driven joints and poses move toward their
    // setpoints (at JOINT_SPEED and DRIVE_SPEED, times the speed).
    void advance(double seconds);

    // Setpoint streams (--simulate, dds/stream.hpp SimulatedStreams): a stream's setpoints
    // drive the subsystem it names: its joints (a JointSample's positions, in the joint
    // entry's order, clamped to their limits; no subsystem: the first joint entry's) or its pose (a PositionSample's xyz: the pose
    // of the position entry of that subsystem, or the body when the subsystem is empty, a
    // Mobility one or has no position entry of its own). They move there in advance().
    void stream_joints(const std::string& subsystem, const std::vector<double>& positions);
    void stream_pose(const std::string& subsystem, const std::array<double, 3>& xyz);
    // on_loss stop: what the subsystem's stream drives stops where it is.
    void stream_halt(const std::string& subsystem);
    // The pose a position entry of this subsystem reports (the body unless a stream drives it).
    Body pose(const std::string& subsystem) const;
    // Positions of the joints a stream of this subsystem drives ("": the first joint entry's).
    std::vector<double> stream_joint_positions(const std::string& subsystem) const;
    // More agent values (the streams' state keys), merged into agent(); called without the
    // simulator's lock held.
    void agent_source(std::function<std::map<std::string, Value>()> values);
    double speed() const { return speed_; }

    // The DDS side takes pictures: called with the index among image entries, from the
    // command's thread. Unset: picture commands fail ("cameras not ready").
    void on_picture(std::function<void(std::size_t)> take);
    // Whether some command of the subsystem takes pictures.
    bool has_picture_command(const std::string& subsystem) const;

private:
    Result drive(CommandContext& ctx, double x, double y, double th);
    Result move_joints(CommandContext& ctx, const std::vector<std::size_t>& targets, const std::vector<double>& numbers);
    Result pictures(CommandContext& ctx, const std::vector<std::size_t>& cameras);
    std::vector<std::size_t> cameras(const CommandContext& ctx) const;
    std::vector<std::size_t> joints_of(const std::string& subsystem) const;
    std::vector<std::size_t> stream_targets(const std::string& subsystem) const;
    bool drives_body(const std::string& subsystem) const;
    static void approach(Body& b, const std::array<double, 3>& goal, double step, double dt);

    const Tables& tables_;
    double speed_;
    mutable std::mutex mutex_;
    Body body_;
    std::vector<double> joint_pos_;  // every joint entry's joints, one after the other
    std::vector<std::pair<std::optional<double>, std::optional<double>>> joint_limits_;
    std::vector<std::string> joint_frames_;
    std::vector<std::size_t> joint_offset_;  // per joint entry: its first joint
    std::map<std::string, Value> agent_;
    std::function<void(std::size_t)> take_picture_;
    // setpoint streams
    std::vector<double> joint_goal_;  // per joint: a stream's setpoint, NaN when none
    std::optional<std::array<double, 3>> body_goal_;
    std::map<std::string, Body> parts_;  // poses of subsystems a stream drives
    std::map<std::string, std::optional<std::array<double, 3>>> part_goal_;
    std::function<std::map<std::string, Value>()> agent_source_;
};

}  // namespace rapid_runtime

#endif
