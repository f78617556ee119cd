"""The registry of diagnostic codes: each code's severity, stage and one-line summary.

Every code the source reports is here and every code here is reported somewhere; the code
tables in docs/*.md are tested against this one (tests/unit/test_codes.py: each code in
exactly one row, its text the summary, with "warning: " / "note: " / "error or warning: "
before it). `-W no-CODE` accepts only codes that can be warnings.

With RAPIDGEN_CHECK_CODES=1 in the environment (the test suite sets it) every diagnostic
is checked as it is reported: an unregistered code, or one reported with a severity the
registry does not give it, raises UnregisteredCode (the CLI's internal error, exit 3).
"""
from __future__ import annotations

import os
from typing import Literal, NamedTuple

Severity = Literal["error", "warning", "note", "error or warning"]
Stage = Literal["input", "preprocess", "parse", "resolve", "driver", "project", "writer", "generate",
                "vectors", "descriptor", "qos", "python", "cpp", "rust", "diff", "cmd", "init", "secure"]


class Code(NamedTuple):
    code: str
    severity: Severity
    stage: Stage  # the part of rapidgen that reports it
    summary: str  # what it means, as the docs' table says it

    def allows(self, severity: str) -> bool:
        """Whether a diagnostic of this code may have `severity` ("error", "warning", "note").

        A note comments on the diagnostics above it (how many more schema errors): any
        code that reports errors may carry one."""
        if severity == "note":
            return self.severity in ("note", "error", "error or warning")
        return severity == self.severity or (self.severity == "error or warning" and severity in ("error", "warning"))

    @property
    def doc_text(self) -> str:
        """The meaning column of this code's row in the docs."""
        return self.summary if self.severity == "error" else f"{self.severity}: {self.summary}"


_CODES = (
    Code("RG0001", "error", "input", 'cannot read a file (missing, a directory, unreadable)'),
    Code("RG0002", "error", "input", 'NUL byte: a binary file'),
    Code("RG0003", "error", "input", 'not valid UTF-8'),
    Code("RG0004", "error", "input",
         'no definitions in the input (empty, comments only, all excluded by `#if`)'),
    Code("RG0005", "error", "input",
         'file larger than 16 MiB, or all input files of a run together larger than 16 MiB'),
    Code("RG0006", "error", "input", 'more than 10,000 input files in one run'),
    Code("RG0101", "error", "preprocess", '`#include` file not found (the hint lists the folders searched)'),
    Code("RG0102", "error", "preprocess", 'include cycle'),
    Code("RG0103", "error", "preprocess", 'includes nested more than 64 deep'),
    Code("RG0104", "error", "preprocess", 'unbalanced `#if`/`#else`/`#endif`'),
    Code("RG0105", "error", "preprocess", 'unknown preprocessor directive'),
    Code("RG0106", "error", "preprocess", '`#if` expression cannot be evaluated'),
    Code("RG0107", "error", "preprocess",
         'malformed directive (missing macro name, function-like macro, bad `#include`, longer than 64 KiB)'),
    Code("RG0108", "error", "preprocess", 'unterminated `/*` comment'),
    Code("RG0109", "error", "preprocess", '`#error`'),
    Code("RG0110", "warning", "preprocess", '`#pragma` ignored'),
    Code("RG0111", "warning", "preprocess", '`#warning`'),
    Code("RG0112", "warning", "preprocess", 'an `-I` folder does not exist'),
    Code("RG0113", "error", "preprocess",
         'a macro use expands to more than 64 Ki characters, or all expansions add more than 64 MiB'),
    Code("RG0201", "error", "parse",
         'syntax error (expected ..., missing `;`, unclosed `{`, reserved word as a name, interfaces); input nested too deeply (modules over 100 deep, a very deep expression)'),
    Code("RG0202", "error", "parse", 'unexpected character, unterminated string, bad character literal'),
    Code("RG0203", "error", "resolve", 'unknown name (type, base, constant), with a did-you-mean'),
    Code("RG0204", "error", "resolve", 'name already defined'),
    Code("RG0205", "error", "resolve", 'duplicate member'),
    Code("RG0206", "error", "resolve", 'a name used as a type is not a type'),
    Code("RG0207", "error", "resolve", 'map key is not an integer or string type'),
    Code("RG0301", "error", "resolve", "base is not a struct (or a bitset's base not a bitset)"),
    Code("RG0302", "error", "resolve", 'circular inheritance or definition'),
    Code("RG0303", "error", "resolve", 'a type contains itself by value'),
    Code("RG0304", "error", "resolve", 'duplicate union case label'),
    Code("RG0306", "error", "resolve", 'more than one `default` label'),
    Code("RG0307", "error", "resolve", 'bad union discriminator type'),
    Code("RG0308", "error", "resolve", 'duplicate enumerator or bit value (name or value)'),
    Code("RG0309", "error", "resolve", 'forward-declared type never defined'),
    Code("RG0310", "error", "resolve", '`#pragma keylist`: unknown member, or not a struct'),
    Code("RG0312", "warning", "resolve", 'members differ only in case'),
    Code("RG0401", "error", "resolve", 'type mismatch in a constant expression, operator on the wrong operand'),
    Code("RG0402", "error", "resolve",
         'overflow: a value does not fit its type (or 64 bits), shift out of range; an integer literal over 40 digits or a fixed-point literal over 31; a string longer than its bound anywhere but a const declaration (e.g. a @default)'),
    Code("RG0403", "error", "resolve", 'division or remainder by zero'),
    Code("RG0404", "error", "resolve", 'bound, array size or fixed digits not positive'),
    Code("RG0405", "error", "resolve", 'a name used as a constant is not a constant'),
    Code("RG0406", "warning", "resolve",
         'a const declaration\'s string longer than its bound (`const String16 K = "ATHLETE_HEADING_RAD";`): the whole value is kept, as RTI\'s compiler does'),
    Code("RG0501", "warning", "resolve", 'unknown annotation ignored'),
    Code("RG0502", "error", "resolve", 'bad annotation parameters'),
    Code("RG0503", "warning", "resolve", 'annotation has no effect where it is applied'),
    Code("RG0504", "error", "resolve",
         'conflicting annotations (`@final` with `@mutable`, `@key` with `@optional`)'),
    Code("RG0801", "error", "driver", '`generate`: an asset descriptor mixed with IDL files'),
    Code("RG0802", "error", "driver", '`generate`/`check`: unknown or unavailable target language'),
    Code("RG0803", "error", "driver", 'an output file or folder cannot be written'),
    Code("RG0810", "error", "project", 'project file (rapidgen.yaml) cannot be read'),
    Code("RG0811", "error", "project", 'project file larger than 1 MiB or not UTF-8'),
    Code("RG0812", "error", "project",
         'project file: schema violation (a note counts those beyond the first 50)'),
    Code("RG0813", "error", "project", 'project file: no IDL file matches a glob'),
    Code("RG0814", "error", "project", 'project file: two targets with one name, or sharing an output folder'),
    Code("RG0815", "error", "project",
         'project file: an output folder outside the project (absolute, `..`, or through a link)'),
    Code("RG0820", "error", "writer",
         'a back end produced an unsafe output path (absolute, `..`, reserved, twice): a bug; nothing written'),
    Code("RG0821", "warning", "writer",
         'a manifest entry (or the whole manifest) is unusable, e.g. a path outside the output folder; ignored, never deleted'),
    Code("RG0822", "error or warning", "writer",
         'a symbolic link in the output folder: never written or deleted through (error on a path to write, '
         'warning on a stale manifest entry or a linked manifest)'),
    Code("RG0823", "error", "writer",
         'something rapidgen did not write is in the way of a generated file (a file not in the manifest, a folder); nothing written'),
    Code("RG0824", "error", "writer",
         'another run kept the output folder locked too long (`generate`/`check` wait up to 60 s)'),
    Code("RG0830", "error", "generate",
         "generation: a generated file would hold a character its format cannot carry (XML 1.0's forbidden characters, lone surrogates); located at the descriptor field when one holds it"),
    Code("RG0901", "error", "vectors", '`vectors`: a type declared differently by two inputs'),
    Code("RG0902", "error", "vectors", '`vectors`: a sample the encoder refuses (a bug)'),
    Code("RG0903", "error", "vectors", '`vectors`: an array too large to sample'),
    Code("RG1001", "error", "descriptor", 'cannot read the descriptor (missing, a directory)'),
    Code("RG1002", "error", "descriptor", 'NUL byte: a binary file'),
    Code("RG1003", "error", "descriptor", 'not valid UTF-8'),
    Code("RG1004", "error", "descriptor", 'file larger than 8 MiB'),
    Code("RG1010", "error", "descriptor",
         'YAML syntax error (including several documents, tabs, control characters); a misindented line is an "indentation error" naming the offending line and the line it fails to line up with'),
    Code("RG1011", "error", "descriptor", 'duplicate mapping key'),
    Code("RG1012", "error", "descriptor",
         'unsupported YAML: tags, merge keys (`<<`), non-scalar keys, recursive aliases, more than 200,000 values (as written or after aliases), nesting deeper than 64'),
    Code("RG1013", "error", "descriptor", 'non-finite number (`.inf`, `.nan`)'),
    Code("RG1014", "error", "descriptor",
         'a string or key holds a control character, a noncharacter or a surrogate (tab and line feed: only in `description`)'),
    Code("RG1020", "error", "descriptor", 'schema: missing key (or an empty descriptor)'),
    Code("RG1021", "error", "descriptor",
         'schema: unknown key (after unquoted text in `{ }`: the hint says a comma ended that value, quote it); `min`/`max` given with `range`'),
    Code("RG1022", "error", "descriptor",
         "schema: wrong type (hint: quote it, for YAML's `on`/`yes`/`1` where text is expected; numbers in `allowed` of a numeric value: use a range instead)"),
    Code("RG1023", "error", "descriptor", 'schema: value not allowed (enum, const)'),
    Code("RG1024", "error", "descriptor", 'schema: number out of bounds (rate <= 0, domain > 232, width < 1)'),
    Code("RG1025", "error", "descriptor", 'schema: malformed name, suffix, MIME type or topic'),
    Code("RG1026", "error", "descriptor", 'schema: empty or repeated list items'),
    Code("RG1027", "note", "descriptor", 'how many schema errors beyond the first 50 were not printed'),
    Code("RG1029", "error", "descriptor", 'schema: any other violation'),
    Code("RG1101", "error", "descriptor",
         'duplicate name (subsystem type, subsystem, command, parameter, value key, joint, source) or an inherited command redefined'),
    Code("RG1102", "error", "descriptor", 'unknown subsystem type (or `extends` of a non-standard type)'),
    Code("RG1103", "error", "descriptor", 'unknown subsystem (telemetry `subsystem`, access pattern)'),
    Code("RG1104", "error", "descriptor", 'unknown command in an access pattern'),
    Code("RG1105", "error", "descriptor", 'a subsystem type redefines a standard one'),
    Code("RG1106", "error", "descriptor", 'name or string longer than its IDL string bound'),
    Code("RG1107", "error", "descriptor",
         'more items than an IDL sequence holds (parameters, commands, joints, values, topics, ...)'),
    Code("RG1108", "warning", "descriptor",
         'a subsystem type has no subsystem (it is left out of the CommandConfig)'),
    Code("RG1201", "error", "descriptor",
         'unknown DataType or RotationEncoding enumerator (the hint lists every DataType)'),
    Code("RG1202", "error", "descriptor", 'a type the ParameterUnion cannot carry'),
    Code("RG1203", "error", "descriptor",
         'min greater than max (the only error then: the default and thresholds are not also checked against the reversed range)'),
    Code("RG1204", "error", "descriptor", 'default of the wrong shape, outside the range or not allowed'),
    Code("RG1205", "error", "descriptor", 'range on a bool/string, `allowed` on a non-string'),
    Code("RG1207", "error", "descriptor", 'a limit or default that does not fit the DataType'),
    Code("RG1301", "error", "descriptor", 'unknown telemetry type'),
    Code("RG1302", "error", "descriptor", 'telemetry type that is not a RAPID message (no rapid::Message base)'),
    Code("RG1303", "error", "descriptor", 'unknown QoS profile'),
    Code("RG1305", "error", "descriptor", 'topic published twice'),
    Code("RG1306", "error", "descriptor", 'inconsistent thresholds'),
    Code("RG1307", "error", "descriptor", 'thresholds on a non-numeric value'),
    Code("RG1308", "error", "descriptor", 'QoS override for a role the entry does not publish'),
    Code("RG1309", "error", "descriptor", 'the RAPID IDL cannot be found'),
    Code("RG1310", "error", "descriptor", 'extension IDL file or include folder not found'),
    Code("RG1311", "error", "descriptor", 'unknown JointSample field'),
    Code("RG1312", "error", "descriptor", 'custom topic names a constant that is not a string constant'),
    Code("RG1313", "error", "descriptor", 'stream type unknown or not a RAPID message'),
    Code("RG1314", "error", "descriptor", 'stream deadline shorter than its period, or liveliness lease shorter than its deadline'),
    Code("RG1315", "error", "descriptor", 'stream topic taken by a publication or another stream'),
    Code("RG1316", "error", "descriptor", 'stream state or missed key not a value of the agent telemetry, or of the wrong type'),
    Code("RG1317", "warning", "descriptor", 'input-only stream setting on an output stream'),
    Code("RG1318", "error", "descriptor",
         'conformance: a motion command that names nothing or does not move the asset, or an argument that does not fit'),
    Code("RG1401", "warning", "descriptor", 'DDS partition differs from the asset name'),
    Code("RG1402", "error", "descriptor", 'malformed access pattern'),
    Code("RG1403", "warning", "descriptor",
         "DDS domain whose RTPS ports lie in Linux's default ephemeral port range (domains 102-214)"),
    Code("RG1501", "error", "descriptor", 'ros2: unknown ROS 2 message type'),
    Code("RG1502", "error", "descriptor", 'ros2: a message has no such field'),
    Code("RG1503", "error", "descriptor", 'ros2: a value, argument or message that does not fit its target'),
    Code("RG1504", "error", "descriptor", 'ros2: unknown command, parameter, telemetry entry or value key'),
    Code("RG1505", "error", "descriptor", 'ros2: malformed section (keys, names, topics)'),
    Code("RG1506", "error", "descriptor", 'ros2: a command mapped twice, or a telemetry entry or value fed twice'),
    Code("RG1507", "warning", "descriptor", 'ros2: a telemetry entry no ROS 2 topic feeds (the bridge never publishes it)'),
    Code("RG1508", "warning", "descriptor",
         'ros2: an advertised command with no ROS 2 mapping (the bridge answers it EXEC_FAILED)'),
    Code("RG1509", "warning", "descriptor", "ros2: BatteryState's 0-1 percentage fed unscaled into a value whose unit is %"),
    Code("RG1601", "error", "qos", 'the file cannot be read, is binary or over 1 MiB'),
    Code("RG1602", "error", "qos",
         'schema: unknown key (with a did-you-mean), wrong type or value, keep_last without depth, keep_all with one'),
    Code("RG1603", "error", "qos", 'unknown base profile'),
    Code("RG1604", "error", "qos", 'inheritance cycle (`A -> B -> A`)'),
    Code("RG1605", "error", "qos", 'the topic map names an unknown profile'),
    Code("RG1606", "error", "qos", 'no default transport, or more than one'),
    Code("RG1607", "warning", "qos", '`multicast_address` with `multicast: false`'),
    Code("RG1608", "error", "qos", 'generation: a topic uses a profile the library lacks'),
    Code("RG1609", "error", "qos",
         'generation: the qos target run without a QoS library (a bug of the caller)'),
    Code("RG1701", "error", "python",
         'a construct the python target cannot express (wchar, wstring, map, fixed, bitset, native, ...), at each use'),
    Code("RG1702", "error", "cpp",
         'a construct the cpp target cannot express (wchar, wstring, map, fixed, bitset, bitmask, native, @optional, @mutable, ...), at each use'),
    Code("RG1703", "error", "rust",
         'a construct the rust target cannot express (wchar, wstring, map, fixed, bitset, bitmask, native, @optional, @mutable, ...), at each use'),
    Code("RG1801", "error", "diff", '`rapidgen diff`: a side does not exist, is not a file or folder, or is a folder without IDL files'),
    Code("RG1802", "error", "diff", '`--against REV`: not a git repository, unknown revision or not a commit (a blob, a tree), or the path is not in it (or is a symbolic link or a submodule there)'),
    Code("RG1803", "error", "diff", '`--against REV`: the revision holds more than 20,000 spec files or 64 MiB of them, more than 1,000,000 entries, or a path longer than 3,800 bytes or more than 100 folders deep'),
    Code("RG1804", "error", "diff", 'malformed waiver file (`--waivers`): shape, unknown rule id, missing reason'),
    Code("RG1805", "error", "diff",
         '`--against REV`: a damaged or crafted repository (a missing or corrupt object, a name that is both a file and a folder or listed twice, a file whose object is not a blob), or a file of the revision cannot be written to the temporary folder'),
    Code("RG1901", "error", "cmd", '`rapidgen cmd`: ASSET is neither a descriptor nor an importable asset package'),
    Code("RG1902", "error", "cmd", '`rapidgen cmd`: the asset has no such subsystem, with a did-you-mean'),
    Code("RG1903", "error", "cmd", '`rapidgen cmd`: the subsystem has no such command, with a did-you-mean'),
    Code("RG1904", "error", "cmd", '`rapidgen cmd`: an argument that is not key=value, an unknown parameter name (did-you-mean), or one given twice'),
    Code("RG1905", "error", "cmd", '`rapidgen cmd`: a value not of its parameter\'s type, outside its range or not one of its allowed values'),
    Code("RG1906", "error", "cmd", '`rapidgen cmd`: a parameter without default is missing'),
    Code("RG1907", "error", "cmd", '`rapidgen cmd`: unknown queue action, `--target` missing or not expected, queue action on an asset without a queue'),
    Code("RG1908", "error", "cmd", '`rapidgen cmd`: no asset reads commands on that domain and partition, or its QoS files cannot be used'),
    Code("RG1909", "error", "cmd", '`rapidgen cmd`: cyclonedds or the runtime (rapid_runtime) is not installed'),
    Code("RG1910", "error", "init", '`rapidgen init`: not an asset name, the file exists (never overwritten), or it cannot be written'),
    Code("RG2001", "error", "secure", '`rapidgen secure`: a deployment file that is malformed or names an unknown asset, a duplicate name, a grant the asset\'s access_control refuses, or a partition with a DDS wildcard'),
    Code("RG2002", "error", "secure", '`rapidgen secure`: two assets of a deployment share a DDS partition on a domain they both use'),
)

REGISTRY: dict[str, Code] = {c.code: c for c in _CODES}


class UnregisteredCode(AssertionError):
    """A diagnostic with a code the registry lacks, or with a severity it does not allow."""


def can_be_silenced(code: str) -> bool:
    """Whether `-W no-CODE` means something: the code is registered and can be a warning."""
    entry = REGISTRY.get(code)
    return entry is not None and entry.allows("warning")


def checking() -> bool:
    """Whether diagnostics are checked against the registry as they are reported."""
    return os.environ.get("RAPIDGEN_CHECK_CODES") == "1"


def check(code: str, severity: str) -> None:
    """Raise UnregisteredCode unless `code` is registered and may have `severity`."""
    entry = REGISTRY.get(code)
    if entry is None:
        raise UnregisteredCode(f"diagnostic code {code!r} is not in rapidgen/codes.py")
    if not entry.allows(severity):
        raise UnregisteredCode(f"{code} is registered as {entry.severity}, reported as {severity}")
