// Serialize / deserialize ns/op of rapidgen's generated C++ and fastddsgen's generated
// code for the same types (fdg::rapid::..., IDL 4 form written by bench/cpp_codec.py),
// beside a memcpy of the same bytes. Prints one line per case; never fails on time.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <rapid_types/types.hpp>

#include "Command.h"
#include "ImageSensorSample.h"
#include "JointSample.h"

using Clock = std::chrono::steady_clock;
static volatile std::size_t sink;

template <class F>
double ns_per_op(F&& f, long iters) {
    double best = 1e300;
    for (int run = 0; run < 5; ++run) {
        auto t0 = Clock::now();
        for (long i = 0; i < iters; ++i) f();
        double ns = std::chrono::duration<double, std::nano>(Clock::now() - t0).count() / static_cast<double>(iters);
        if (ns < best) best = ns;
    }
    return best;
}

template <class Ours, class Theirs>
void bench(const char* name, const Ours& value, long iters) {
    std::vector<std::uint8_t> bytes = rapidgen::cdr::serialize(value);
    std::vector<char> buf(bytes.size() + 1024);
    // ours: into a fixed buffer (as the TopicDataType does), and back into a reused value
    double our_ser = ns_per_op([&] {
        rapidgen::cdr::Writer w(reinterpret_cast<std::uint8_t*>(buf.data()) + 4, buf.size() - 4);
        encode(w, value);
        sink = w.size();
    }, iters);
    Ours back;
    double our_de = ns_per_op([&] { rapidgen::cdr::deserialize(bytes.data(), bytes.size(), back); }, iters);
    if (!(back == value)) std::printf("ours: round trip differs\n");
    // fastddsgen: its object read from the same bytes, then both directions
    Theirs theirs;
    {
        eprosima::fastcdr::FastBuffer fb(reinterpret_cast<char*>(bytes.data()), bytes.size());
        eprosima::fastcdr::Cdr de(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        de.read_encapsulation();
        theirs.deserialize(de);
    }
    double fdg_ser = ns_per_op([&] {
        eprosima::fastcdr::FastBuffer fb(buf.data(), buf.size());
        eprosima::fastcdr::Cdr ser(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        ser.serialize_encapsulation();
        theirs.serialize(ser);
        sink = ser.getSerializedDataLength();
    }, iters);
    {
        eprosima::fastcdr::FastBuffer fb(buf.data(), buf.size());
        eprosima::fastcdr::Cdr ser(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        ser.serialize_encapsulation();
        theirs.serialize(ser);
        bool same = ser.getSerializedDataLength() == bytes.size() && std::memcmp(buf.data(), bytes.data(), bytes.size()) == 0;
        if (!same) std::printf("%s: fastddsgen bytes differ from ours\n", name);
    }
    Theirs theirs_back;
    double fdg_de = ns_per_op([&] {
        eprosima::fastcdr::FastBuffer fb(reinterpret_cast<char*>(bytes.data()), bytes.size());
        eprosima::fastcdr::Cdr de(fb, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
        de.read_encapsulation();
        theirs_back.deserialize(de);
    }, iters);
    double mem = ns_per_op([&] {
        std::memcpy(buf.data(), bytes.data(), bytes.size());
        sink = static_cast<std::size_t>(buf[bytes.size() / 2]);
    }, iters);
    std::printf("%-22s %9zu %12.1f %12.1f %12.1f %12.1f %10.1f %7.2fx %7.2fx\n", name, bytes.size(), our_ser, fdg_ser,
                our_de, fdg_de, mem, fdg_ser / our_ser, fdg_de / our_de);
}

int main() {
    rapid::Command cmd;
    cmd.hdr.srcName = "commander-01";
    cmd.hdr.assetName = "K10Red";
    cmd.hdr.timeStamp = 1700000000000000;
    cmd.cmdName = "driveTo";
    cmd.cmdId = "17-commander-01-1700000000";
    cmd.cmdSrc = "commander-01";
    cmd.subsysName = "Locomotion";
    cmd.arguments.resize(3);
    cmd.arguments[0].s("waypoint-7");
    cmd.arguments[1].d(0.5);
    cmd.arguments[2].vec3d({1.0, 2.0, 3.0});
    cmd.cmdAction = rapid::QueueAction::QUEUE_APPEND;

    rapid::JointSample js;
    js.hdr = cmd.hdr;
    for (auto* s : {&js.anglePos, &js.angleVel, &js.angleAcc, &js.current, &js.torque, &js.temperature}) {
        s->resize(64);
        for (int i = 0; i < 64; ++i) (*s)[static_cast<std::size_t>(i)] = 0.25f * static_cast<float>(i);
    }
    js.status.assign(64, 1);

    rapid::ImageSensorSample img;
    img.hdr = cmd.hdr;
    img.meta.sensorName = "panCamLeft";
    img.meta.width = 1024;
    img.meta.height = 1024;
    img.mimeType = "image/x-raw-gray8";
    img.data.resize(1048576);
    for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = static_cast<std::uint8_t>(i * 31);

    std::printf("%-22s %9s %12s %12s %12s %12s %10s %8s %8s\n", "type", "bytes", "ser ours", "ser fdg", "de ours",
                "de fdg", "memcpy", "ser x", "de x");
    bench<rapid::Command, fdg::rapid::Command>("Command (3 arguments)", cmd, 200000);
    bench<rapid::JointSample, fdg::rapid::JointSample>("JointSample (64)", js, 100000);
    bench<rapid::ImageSensorSample, fdg::rapid::ImageSensorSample>("ImageSensorSample 1MB", img, 300);
    return 0;
}
