"""Robonaut 2's computed CommandConfig against seed 001, tables 3-5, written out by hand.

Table 3 (example commands and addressable subsystems):
    Setpoint for tool (cartesian)   LeftArm, RightArm
    Setpoint for single joint       LeftArm, RightArm, Neck
    Open the Hand                   LeftHand, RightHand
    Close the Hand                  LeftHand, RightHand
Table 4 (Setpoint for Tool; Command Name "Setpoint for Tool"):
    X, Y, Z coordinates [SI meter]  RAPID_VEC3d
    Roll, pitch, yaw [SI rad]       RAPID_VEC3d
    Frame, e.g. "R2OriginFrame"     RAPID_STRING
Table 5 (Setpoint for single joint, Left Arm): 1-7 Float [rad]: abduction, extension,
    upper arm outer rotation, elbow flexion, forearm outer rotation, wrist flexion,
    wrist ulnar flexio(n).
"""

TABLE_3 = {
    "Setpoint for Tool": {"LeftArm", "RightArm"},
    "Setpoint for single joint": {"LeftArm", "RightArm", "Neck"},
    "Open the Hand": {"LeftHand", "RightHand"},
    "Close the Hand": {"LeftHand", "RightHand"},
}
TABLE_4 = [("xyz", "RAPID_VEC3d", "m"), ("rpy", "RAPID_VEC3d", "rad"), ("frame", "RAPID_STRING", None)]
TABLE_5 = [("abduction", "abduction"), ("extension", "extension"),
           ("upperArmOuterRotation", "upper arm outer rotation"), ("elbowFlexion", "elbow flexion"),
           ("forearmOuterRotation", "forearm outer rotation"), ("wristFlexion", "wrist flexion"),
           ("wristUlnarFlexion", "wrist ulnar flexion")]

# The whole CommandConfig (hdr aside), in publication order.
EXPECTED = {
    "availableSubsystemTypes": [
        {"name": "Arm", "commands": [
            {"name": "Setpoint for Tool", "abortable": True, "suspendable": False, "parameters": [
                {"key": "xyz", "type": "RAPID_VEC3d"},
                {"key": "rpy", "type": "RAPID_VEC3d"},
                {"key": "frame", "type": "RAPID_STRING"}]},
            {"name": "Setpoint for single joint", "abortable": True, "suspendable": False, "parameters": [
                {"key": k, "type": "RAPID_FLOAT"} for k, _ in TABLE_5]}]},
        {"name": "Neck", "commands": [
            {"name": "Setpoint for single joint", "abortable": True, "suspendable": False, "parameters": [
                {"key": "lowerPitch", "type": "RAPID_FLOAT"},
                {"key": "yaw", "type": "RAPID_FLOAT"},
                {"key": "upperPitch", "type": "RAPID_FLOAT"}]}]},
        {"name": "Hand", "commands": [
            {"name": "Open the Hand", "abortable": True, "suspendable": False, "parameters": []},
            {"name": "Close the Hand", "abortable": True, "suspendable": False, "parameters": []}]},
    ],
    "availableSubsystems": [
        {"name": "LeftArm", "subsystemTypeName": "Arm"},
        {"name": "RightArm", "subsystemTypeName": "Arm"},
        {"name": "Neck", "subsystemTypeName": "Neck"},
        {"name": "LeftHand", "subsystemTypeName": "Hand"},
        {"name": "RightHand", "subsystemTypeName": "Hand"},
    ],
}


def test_command_config_is_the_papers(seed):
    assert seed("robonaut2").configs["rapid_command_config"][1] == EXPECTED


def test_table_3_commands_and_addressable_subsystems(seed):
    cc = seed("robonaut2").configs["rapid_command_config"][1]
    types = {t["name"]: {c["name"] for c in t["commands"]} for t in cc["availableSubsystemTypes"]}
    addressable = {cmd: {s["name"] for s in cc["availableSubsystems"] if cmd in types[s["subsystemTypeName"]]}
                   for cmd in TABLE_3}
    assert addressable == TABLE_3


def test_table_4_and_5_parameters_with_units(seed):
    arm = next(t for t in seed("robonaut2").spec.subsystem_types if t.name == "Arm")
    tool, joint = arm.commands
    assert [(p.name, p.type, p.unit) for p in tool.parameters] == TABLE_4
    assert [(p.name, p.type, p.unit, p.description) for p in joint.parameters] == \
        [(k, "RAPID_FLOAT", "rad", d) for k, d in TABLE_5]
    assert tool.parameters[2].default == "R2OriginFrame"


def test_telemetry_of_table_1(seed):
    loaded = seed("robonaut2")
    got = loaded.configs
    assert list(got) == ["rapid_command_config", "rapid_agent_config", "rapid_joint_config",
                         "rapid_position_config-leftArm", "rapid_position_config-rightArm"]
    kind, left = got["rapid_position_config-leftArm"]
    assert kind == "rapid::PositionConfig"
    assert left == {"frameName": "R2OriginFrame", "poseEncoding": "RAPID_ROT_M33",
                    "velocityEncoding": "RAPID_ROT_NONE", "valueKeys": []}
    _, joints = got["rapid_joint_config"]
    assert joints["jointGroupName"] == "R2" and len(joints["jointDefinitions"]) == 18
    assert joints["jointDefinitions"][3] == {"frameName": "LeftArm/Joint3", "dof": "elbowFlexion"}
    _, agent = got["rapid_agent_config"]
    assert agent["valueKeys"][0] == {"key": "leftWristForce", "padding": 0,
                                     "value": {"discriminator": "RAPID_VEC3d", "value": [0.0, 0.0, 0.0]}}
    assert "rapid_position_sample-leftArm" in agent["topics"]
    assert loaded.facts.shapes["RAPID_VEC3d"].count == 3
