// K10Red as constant data (see k10_tables.hpp): one brace initializer, as generated code
// would spell it.
#include "k10_tables.hpp"

using namespace rapid_runtime;

namespace {

const DataType S = DataType::String, F = DataType::Float, V = DataType::Vec3d, M = DataType::Mat33f,
               I = DataType::Int;

Param plain(std::string name, DataType type, std::string unit = {}) {
    Param p;
    p.name = std::move(name);
    p.type = type;
    p.unit = std::move(unit);
    return p;
}

Param ranged(std::string name, DataType type, std::string unit, double min, double max) {
    Param p = plain(std::move(name), type, std::move(unit));
    p.min = min;
    p.max = max;
    return p;
}

CommandSpec command(std::string name, std::vector<Param> params, bool abortable = false, bool suspendable = false,
                    bool standard = true) {
    CommandSpec c;
    c.name = std::move(name);
    c.params = std::move(params);
    c.abortable = abortable;
    c.suspendable = suspendable;
    c.standard = standard;
    return c;
}

Tables build() {
    Tables t;
    t.name = "K10Red";
    t.kind = "rover";
    t.domain = 0;
    t.partition = "K10Red";
    t.subsystems = {{"Admin", "Admin"}, {"Mobility", "Mobility"}, {"Queue", "Queue"},
                    {"AccessControl", "AccessControl"}, {"PanCam", "PanTiltCamera"}, {"HazCams", "ImageSensor"},
                    {"K10Native", "K10Native"}};
    Param mode = plain("mode", S);
    mode.allowed = {Value(std::string("left")), Value(std::string("right")), Value(std::string("stereo"))};
    mode.default_value = Value(std::string("stereo"));
    Param tiles = ranged("tiles", I, "", 1, 64);
    tiles.default_value = Value(std::int32_t{8});
    t.types = {
        {"Admin", {command("echo", {plain("text", S)}), command("shutdown", {}), command("noOp", {})}},
        {"Mobility",
         {command("stopAllMotion", {}),
          command("simpleMove", {plain("frame", S), plain("xyt", V, "m, m, rad")}, true, true),
          command("move", {plain("frame", S), plain("xyt", V, "m, m, rad"), plain("xytTolerance", V, "m, m, rad")},
                  true, true),
          command("move6DOF", {plain("frame", S), plain("xyz", V, "m"), plain("rot", M)}, true, true)}},
        {"Queue", {command("cancelAll", {}), command("loadMacro", {plain("name", S)})}},
        {"AccessControl",
         {command("requestControl", {}), command("grabControl", {}), command("releaseControl", {}),
          command("transferControl", {plain("newController", S)})}},
        {"PanTiltCamera",
         {command("pointCamera", {ranged("pan", F, "rad", -3.05, 3.05), ranged("tilt", F, "rad", -1.4, 1.4)}, true,
                  false, false),
          command("takePicture", {mode, ranged("exposure", F, "ms", 0, 2000)}, false, false, false),
          command("takePanorama",
                  {ranged("panStart", F, "rad", -3.05, 3.05), ranged("panEnd", F, "rad", -3.05, 3.05),
                   ranged("tilt", F, "rad", -1.4, 1.4), tiles},
                  true, true, false)}},
        {"ImageSensor", {}},
        {"K10Native", {command("nativeCommand", {plain("text", S)}, false, false, false)}},
    };
    t.access = AccessSpec{
        false,
        {{"RapidWorkbench", {"*"}},
         {"MultiCenterCockpit", {"Mobility/*", "PanCam/*", "Queue/*", "Admin/echo", "AccessControl/*"}},
         {"ScienceBackroom", {"PanCam/takePicture", "PanCam/takePanorama", "Admin/echo"}}}};
    return t;
}

}  // namespace

const Tables& k10_tables() {
    static const Tables tables = build();
    return tables;
}
