#include "rapid_runtime/simulator.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <regex>

namespace rapid_runtime {
namespace {

constexpr double TAU = 6.283185307179586;

std::string lower(std::string s) {
    for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

Value number_of(DataType t, double x) {
    switch (t) {
        case DataType::Double: return x;
        case DataType::Float: return static_cast<float>(x);
        case DataType::Int: return static_cast<std::int32_t>(x);
        case DataType::LongLong: return static_cast<std::int64_t>(x);
        case DataType::Bool: return x != 0.0;
        case DataType::String: return std::string();
        case DataType::Vec3d: return Vec3d{x, x, x};
        case DataType::Mat33f: return Mat33f{};
    }
    return x;
}

// A value key's first value (simulate.py's _initial): its default; a battery full (charge,
// %) or at 85% of its range; the middle of a range; 20 for another number.
Value initial(const Param& v) {
    if (v.default_value) return *v.default_value;
    std::string name = lower(v.name);
    if (v.type == DataType::Float || v.type == DataType::Double) {
        if (contains(name, "battery") && v.max) {
            double x = contains(name, "charge") || v.unit == "%" ? *v.max : (*v.max + v.min.value_or(0.0)) * 0.85;
            return number_of(v.type, x);
        }
        if (v.min && v.max) return number_of(v.type, (*v.min + *v.max) / 2);
        return number_of(v.type, 20.0);
    }
    switch (v.type) {
        case DataType::String: return v.allowed.empty() ? Value(std::string()) : v.allowed.front();
        case DataType::Int: return static_cast<std::int32_t>(v.min.value_or(0.0));
        case DataType::LongLong: return std::int64_t{0};
        case DataType::Vec3d: return Vec3d{};
        case DataType::Mat33f: return Mat33f{};
        default: return false;
    }
}

double clamp(double x, const std::pair<std::optional<double>, std::optional<double>>& lim) {
    if (lim.first) x = std::max(x, *lim.first);
    if (lim.second) x = std::min(x, *lim.second);
    return x;
}

bool is_vec3(const std::vector<Value>& args, std::size_t i) {
    return i < args.size() && std::holds_alternative<Vec3d>(args[i]);
}

std::string fixed2(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", x);
    return buf;
}

}  // namespace

bool picture_command(const std::string& name) {
    static const std::regex words("picture|image|photo|snap|capture|panorama|acquire|shoot", std::regex::icase);
    return std::regex_search(name, words);
}

Simulator::Simulator(const Tables& tables, double speed) : tables_(tables), speed_(std::max(speed, 1e-3)) {
    for (const auto& t : tables.telemetry) {
        if (t.kind == "joint") {
            joint_offset_.push_back(joint_pos_.size());
            for (const auto& j : t.joints) {
                joint_frames_.push_back(j.frame);
                joint_limits_.emplace_back(j.min, j.max);
                joint_pos_.push_back(clamp(0.0, joint_limits_.back()));
                joint_goal_.push_back(std::nan(""));
            }
        } else if (t.kind == "agent") {
            for (const auto& v : t.values) agent_[v.name] = initial(v);
        }
    }
}

Simulator::Body Simulator::body() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return body_;
}

std::vector<double> Simulator::joints(std::size_t joint_entry) const {
    std::lock_guard<std::mutex> lock(mutex_);
    const TelemetrySpec* t = tables_.telemetry_of("joint", joint_entry);
    if (t == nullptr || joint_entry >= joint_offset_.size()) return {};
    auto first = joint_pos_.begin() + static_cast<std::ptrdiff_t>(joint_offset_[joint_entry]);
    return std::vector<double>(first, first + static_cast<std::ptrdiff_t>(t->joints.size()));
}

std::map<std::string, Value> Simulator::agent() const {
    std::function<std::map<std::string, Value>()> more;
    std::map<std::string, Value> out;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        out = agent_;
        more = agent_source_;
    }
    if (more)
        for (auto& [k, v] : more()) out[k] = std::move(v);
    return out;
}

void Simulator::agent_source(std::function<std::map<std::string, Value>()> values) {
    std::lock_guard<std::mutex> lock(mutex_);
    agent_source_ = std::move(values);
}

bool Simulator::drives_body(const std::string& subsystem) const {
    if (subsystem.empty()) return true;
    const std::string* type = tables_.type_of(subsystem);
    if (type != nullptr && *type == "Mobility") return true;
    for (const auto& t : tables_.telemetry)
        if (t.kind == "position" && t.subsystem == subsystem) return false;
    return true;
}

std::vector<std::size_t> Simulator::stream_targets(const std::string& subsystem) const {
    if (!subsystem.empty()) return joints_of(subsystem);  // (none for one without joints: a drive)
    std::vector<std::size_t> own;
    if (!joint_offset_.empty()) {  // no subsystem named: the first joint entry's
        const TelemetrySpec* t = tables_.telemetry_of("joint", 0);
        for (std::size_t j = 0; t != nullptr && j < t->joints.size(); ++j) own.push_back(joint_offset_[0] + j);
    }
    return own;
}

void Simulator::stream_joints(const std::string& subsystem, const std::vector<double>& positions) {
    auto targets = stream_targets(subsystem);
    std::lock_guard<std::mutex> lock(mutex_);
    for (std::size_t k = 0; k < targets.size() && k < positions.size(); ++k)
        if (std::isfinite(positions[k])) joint_goal_[targets[k]] = clamp(positions[k], joint_limits_[targets[k]]);
}

void Simulator::stream_pose(const std::string& subsystem, const std::array<double, 3>& xyz) {
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) return;
    bool body = drives_body(subsystem);
    std::lock_guard<std::mutex> lock(mutex_);
    if (body) {
        body_goal_ = xyz;
    } else {
        parts_.try_emplace(subsystem);
        part_goal_[subsystem] = xyz;
    }
}

void Simulator::stream_halt(const std::string& subsystem) {
    auto targets = stream_targets(subsystem);
    bool body = drives_body(subsystem);
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto i : targets) joint_goal_[i] = std::nan("");
    if (body) {
        body_goal_.reset();
        body_.velocity = {0.0, 0.0, 0.0};
    } else if (parts_.count(subsystem)) {
        part_goal_[subsystem].reset();
        parts_[subsystem].velocity = {0.0, 0.0, 0.0};
    }
}

Simulator::Body Simulator::pose(const std::string& subsystem) const {
    std::lock_guard<std::mutex> lock(mutex_);
    auto found = parts_.find(subsystem);
    return found != parts_.end() ? found->second : body_;
}

std::vector<double> Simulator::stream_joint_positions(const std::string& subsystem) const {
    auto targets = stream_targets(subsystem);
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<double> out;
    for (auto i : targets) out.push_back(joint_pos_[i]);
    return out;
}

void Simulator::approach(Body& b, const std::array<double, 3>& goal, double step, double dt) {
    double d[3] = {goal[0] - b.xyz[0], goal[1] - b.xyz[1], goal[2] - b.xyz[2]};
    double dist = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    double k = dist > step ? step / dist : 1.0;
    for (int i = 0; i < 3; ++i) {
        b.xyz[i] += d[i] * k;
        b.velocity[i] = dt > 0 ? d[i] * k / dt : 0.0;
    }
    b.odometer += dist * k;
}

void Simulator::advance(double seconds) {
    std::lock_guard<std::mutex> lock(mutex_);
    double dt = std::max(0.0, seconds) * speed_;
    for (std::size_t i = 0; i < joint_pos_.size(); ++i) {
        if (std::isnan(joint_goal_[i])) continue;
        double most = sim::JOINT_SPEED * dt;
        joint_pos_[i] += std::max(-most, std::min(most, joint_goal_[i] - joint_pos_[i]));
    }
    if (body_goal_) approach(body_, *body_goal_, sim::DRIVE_SPEED * dt, dt);
    for (auto& [name, goal] : part_goal_)
        if (goal) approach(parts_[name], *goal, sim::DRIVE_SPEED * dt, dt);
    for (auto& [key, value] : agent_) {
        std::string k = lower(key);
        if (!contains(k, "battery") || !(contains(k, "charge") || contains(k, "%"))) continue;
        if (auto* f = std::get_if<float>(&value))
            *f = static_cast<float>(std::max(0.0, *f - sim::DRAIN * seconds * speed_));
        else if (auto* d = std::get_if<double>(&value))
            *d = std::max(0.0, *d - sim::DRAIN * seconds * speed_);
    }
}

void Simulator::on_picture(std::function<void(std::size_t)> take) {
    std::lock_guard<std::mutex> lock(mutex_);
    take_picture_ = std::move(take);
}

bool Simulator::has_picture_command(const std::string& subsystem) const {
    const std::string* type = tables_.type_of(subsystem);
    const SubsystemType* t = type ? tables_.subsystem_type(*type) : nullptr;
    if (t == nullptr) return false;
    for (const auto& c : t->commands)
        if (picture_command(c.name)) return true;
    return false;
}

Result Simulator::execute(CommandContext& ctx) {
    const std::string& type = ctx.type();
    const std::string& name = ctx.command();
    const auto& args = ctx.args();
    if (type == "Mobility" && name == "stopAllMotion") {
        std::lock_guard<std::mutex> lock(mutex_);
        body_.velocity = {0.0, 0.0, 0.0};
        body_goal_.reset();  // a stream's setpoint too
        return Result::ok("stopped (simulated)");
    }
    if (type == "Mobility" && (name == "simpleMove" || name == "move") && is_vec3(args, 1)) {
        const auto& xyt = std::get<Vec3d>(args[1]);
        return drive(ctx, xyt[0], xyt[1], xyt[2]);
    }
    if (type == "Mobility" && name == "move6DOF" && is_vec3(args, 1)) {
        const auto& xyz = std::get<Vec3d>(args[1]);
        return drive(ctx, xyz[0], xyz[1], body().heading);
    }
    if (type == "Queue" && name == "loadMacro" && !args.empty() && std::holds_alternative<std::string>(args[0]))
        return Result::ok("macro " + std::get<std::string>(args[0]).substr(0, 40) + " is empty (simulated)");
    auto cams = cameras(ctx);
    if (!cams.empty()) return pictures(ctx, cams);
    auto targets = joints_of(ctx.subsystem());
    std::vector<double> numbers;
    for (const auto& a : args) {
        if (auto* d = std::get_if<double>(&a)) numbers.push_back(*d);
        else if (auto* f = std::get_if<float>(&a)) numbers.push_back(*f);
        else if (auto* i = std::get_if<std::int32_t>(&a)) numbers.push_back(*i);
        else if (auto* l = std::get_if<std::int64_t>(&a)) numbers.push_back(static_cast<double>(*l));
        else if (auto* v = std::get_if<Vec3d>(&a)) numbers.insert(numbers.end(), v->begin(), v->end());
        else if (auto* m = std::get_if<Mat33f>(&a)) numbers.insert(numbers.end(), m->begin(), m->end());
    }
    if (!targets.empty() && !numbers.empty()) return move_joints(ctx, targets, numbers);
    if (!ctx.sleep(0.05 / speed_)) throw Cancelled();
    return Result::ok("done (simulated)");
}

Result Simulator::drive(CommandContext& ctx, double x, double y, double th) {
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(th)) return Result::failed("goal not finite");
    for (;;) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            double dx = x - body_.xyz[0], dy = y - body_.xyz[1];
            double dist = std::hypot(dx, dy);
            double dth = std::remainder(th - body_.heading, TAU);
            if (dist < 1e-3 && std::abs(dth) < 1e-3) {
                body_.velocity = {0.0, 0.0, 0.0};
                return Result::ok("arrived at " + fixed2(x) + ", " + fixed2(y));
            }
            double step = std::min(dist, sim::DRIVE_SPEED * sim::TICK * speed_);
            if (dist > 0) {
                body_.xyz[0] += dx / dist * step;
                body_.xyz[1] += dy / dist * step;
                body_.odometer += step;
            }
            double turn_max = sim::TURN_SPEED * sim::TICK * speed_;
            body_.heading += std::max(-turn_max, std::min(turn_max, dth));
            body_.velocity = {dist > 0 ? dx / dist * sim::DRIVE_SPEED : 0.0,
                              dist > 0 ? dy / dist * sim::DRIVE_SPEED : 0.0, 0.0};
        }
        if (!ctx.sleep(sim::TICK)) {
            std::lock_guard<std::mutex> lock(mutex_);
            body_.velocity = {0.0, 0.0, 0.0};
            throw Cancelled();
        }
    }
}

std::vector<std::size_t> Simulator::joints_of(const std::string& subsystem) const {
    std::vector<std::size_t> own;
    for (std::size_t i = 0; i < joint_frames_.size(); ++i)
        if (joint_frames_[i].substr(0, joint_frames_[i].find('/')) == subsystem) own.push_back(i);
    if (!own.empty()) return own;
    std::size_t k = 0;
    for (const auto& t : tables_.telemetry) {
        if (t.kind != "joint") continue;
        if (t.subsystem == subsystem) {
            for (std::size_t j = 0; j < t.joints.size(); ++j) own.push_back(joint_offset_[k] + j);
            return own;
        }
        ++k;
    }
    return own;
}

Result Simulator::move_joints(CommandContext& ctx, const std::vector<std::size_t>& targets,
                              const std::vector<double>& numbers) {
    std::map<std::size_t, double> goal;
    for (std::size_t k = 0; k < targets.size() && k < numbers.size(); ++k)
        goal[targets[k]] = std::isnan(numbers[k]) ? 0.0 : clamp(numbers[k], joint_limits_[targets[k]]);
    for (;;) {
        double left = 0.0;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            double most = sim::JOINT_SPEED * sim::TICK * speed_;
            for (const auto& [i, g] : goal) {
                double d = g - joint_pos_[i];
                double step = std::max(-most, std::min(most, d));
                joint_pos_[i] += step;
                left = std::max(left, std::abs(d - step));
            }
        }
        if (left < 1e-4) return Result::ok(std::to_string(goal.size()) + " joint(s) at setpoint");
        if (!ctx.sleep(sim::TICK)) throw Cancelled();
    }
}

std::vector<std::size_t> Simulator::cameras(const CommandContext& ctx) const {
    if (!picture_command(ctx.command())) return {};
    std::vector<std::size_t> own;
    std::vector<std::string> names;
    std::size_t k = 0;
    for (const auto& t : tables_.telemetry) {
        if (t.kind != "image") continue;
        if (t.subsystem == ctx.subsystem()) {
            own.push_back(k);
            names.push_back(lower(t.sensor + " " + t.sensor_type));
        }
        ++k;
    }
    std::vector<std::string> words;
    for (const auto& a : ctx.args())
        if (auto* s = std::get_if<std::string>(&a))
            if (!s->empty()) words.push_back(lower(*s));
    std::vector<std::size_t> named;
    for (std::size_t i = 0; i < own.size(); ++i)
        for (const auto& w : words)
            if (contains(names[i], w)) {
                named.push_back(own[i]);
                break;
            }
    return named.empty() ? own : named;
}

Result Simulator::pictures(CommandContext& ctx, const std::vector<std::size_t>& cams) {
    std::function<void(std::size_t)> take;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        take = take_picture_;
    }
    if (!take) return Result::failed("cameras not ready yet (simulated)");
    std::string sensors;
    for (auto i : cams) {
        if (!ctx.sleep(0.05 / speed_)) throw Cancelled();
        take(i);
        const TelemetrySpec* t = tables_.telemetry_of("image", i);
        sensors += (sensors.empty() ? "" : ", ") + (t ? t->sensor : std::string());
    }
    return Result::ok(std::to_string(cams.size()) + " picture(s) taken: " + sensors + " (simulated)");
}

}  // namespace rapid_runtime
