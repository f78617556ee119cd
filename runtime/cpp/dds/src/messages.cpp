#include "rapid_runtime/dds/messages.hpp"

#include <chrono>

namespace rapid_runtime {
namespace dds {

std::int64_t now_us() {
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

::rapid::Header header(const std::string& src, const std::string& asset, std::int32_t serial, std::int32_t status) {
    ::rapid::Header h;
    h.srcName = src;
    h.assetName = asset;
    h.timeStamp = now_us();
    h.statusCode = status;
    h.serial = serial;
    return h;
}

Value value_of(const ::rapid::ParameterUnion& u) {
    switch (u._d()) {
        case ::rapid::DataType::RAPID_BOOL: return u.b();
        case ::rapid::DataType::RAPID_DOUBLE: return u.d();
        case ::rapid::DataType::RAPID_FLOAT: return u.f();
        case ::rapid::DataType::RAPID_INT: return u.i();
        case ::rapid::DataType::RAPID_LONGLONG: return u.ll();
        case ::rapid::DataType::RAPID_STRING: return u.s();
        case ::rapid::DataType::RAPID_VEC3d: return Vec3d(u.vec3d());
        case ::rapid::DataType::RAPID_MAT33f: return Mat33f(u.mat33f());
    }
    return false;  // (the decoder admits declared enumerators only)
}

::rapid::ParameterUnion union_of(const Value& v) {
    ::rapid::ParameterUnion u;
    switch (type_of(v)) {
        case DataType::Bool: u.b(std::get<bool>(v)); break;
        case DataType::Double: u.d(std::get<double>(v)); break;
        case DataType::Float: u.f(std::get<float>(v)); break;
        case DataType::Int: u.i(std::get<std::int32_t>(v)); break;
        case DataType::LongLong: u.ll(std::get<std::int64_t>(v)); break;
        case DataType::String: u.s(std::get<std::string>(v)); break;
        case DataType::Vec3d: u.vec3d(std::get<Vec3d>(v)); break;
        case DataType::Mat33f: u.mat33f(std::get<Mat33f>(v)); break;
    }
    return u;
}

Cmd command_in(const ::rapid::Command& c) {
    Cmd out;
    out.cmd_id = c.cmdId;
    out.cmd_src = c.cmdSrc;
    out.subsystem = c.subsysName;
    out.name = c.cmdName;
    out.args.reserve(c.arguments.size());
    for (const auto& a : c.arguments) out.args.push_back(value_of(a));
    out.action = static_cast<QueueAction>(static_cast<std::int32_t>(c.cmdAction));
    out.target = c.targetCmdId;
    out.src_name = c.hdr.srcName;
    out.asset_name = c.hdr.assetName;
    out.serial = c.hdr.serial;
    out.stamp = c.hdr.timeStamp;
    out.status_code = c.hdr.statusCode;
    return out;
}

::rapid::Command command_out(const Cmd& c) {
    ::rapid::Command out;
    out.hdr.srcName = c.src_name;
    out.hdr.assetName = c.asset_name;
    out.hdr.timeStamp = c.stamp;
    out.hdr.statusCode = c.status_code;
    out.hdr.serial = c.serial;
    out.cmdName = c.name;
    out.cmdId = c.cmd_id;
    out.cmdSrc = c.cmd_src;
    out.subsysName = c.subsystem;
    for (const auto& a : c.args) out.arguments.push_back(union_of(a));
    out.cmdAction = static_cast<::rapid::QueueAction>(static_cast<std::int32_t>(c.action));
    out.targetCmdId = c.target;
    return out;
}

void fill_ack(::rapid::Ack& ack, const Cmd& cmd, AckStatus status, Completion completed, const std::string& message) {
    ack.hdr.srcName = cmd.src_name;
    ack.hdr.assetName = cmd.asset_name;
    ack.hdr.timeStamp = now_us();
    ack.hdr.statusCode = 0;
    ack.hdr.serial = cmd.serial;
    ack.cmdId = cmd.cmd_id;
    ack.status = static_cast<::rapid::AckStatus>(static_cast<std::int32_t>(status));
    ack.completedStatus = static_cast<::rapid::AckCompletedStatus>(static_cast<std::int32_t>(completed));
    ack.message = message;
}

namespace {

::rapid::SingleQueue records(const std::vector<Record>& in) {
    ::rapid::SingleQueue q;
    q.records.reserve(in.size());
    for (const auto& r : in) {
        ::rapid::CommandRecord rec;
        rec.cmd = command_out(*r.cmd);
        rec.trResult = static_cast<::rapid::ResultType>(static_cast<std::int32_t>(r.result));
        rec.trStatus = static_cast<::rapid::StatusType>(static_cast<std::int32_t>(r.status));
        q.records.push_back(std::move(rec));
    }
    return q;
}

}  // namespace

::rapid::QueueState queue_state(const ::rapid::Header& hdr, const std::vector<Record>& pending,
                                const std::vector<Record>& active, const std::vector<Record>& completed) {
    ::rapid::QueueState q;
    q.hdr = hdr;
    q.pending = records(pending);
    q.active = records(active);
    q.completed = records(completed);
    return q;
}

}  // namespace dds
}  // namespace rapid_runtime
