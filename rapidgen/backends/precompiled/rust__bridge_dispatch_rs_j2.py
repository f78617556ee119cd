# mypy: ignore-errors
# Template templates/rust/bridge/dispatch.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "8d0db4dd5ea52a2f25e06ab42d087dfcb56e34aa7848ba8601ca16363a1d21d4"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'bridge/dispatch.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_v = resolve('v')
    l_0_st = resolve('st')
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield '\n//! The command handlers of asset '
    yield str(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'asset'))
    yield ": one trait per subsystem type, one method per\n//! command with its arguments by name and type (already checked against the descriptor:\n//! types, ranges, allowed values). Implement them in handlers.rs (yours: rapidgen writes it\n//! once and never again) and return them from make_handlers().\n//!\n//! A method runs on a thread of its own and may run long. Return Outcome::Ok(text) for\n//! COMPLETED/OK (text: Ack.message, cut to 127 bytes), Outcome::Failed(why) for\n//! COMPLETED/EXEC_FAILED (a panic is answered EXEC_FAILED too); ctx.progress(text) sends an\n//! EXECUTING ack; stop early when ctx.cancelled() (ctx.sleep(d) returns false then) and\n//! return Outcome::Canceled. ctx.subsystem() names the instance addressed (two subsystems\n//! may share a type). The standard Admin, Queue and AccessControl commands are the runtime's.\n#![allow(dead_code)]\n// one parameter per declared command parameter, however many the descriptor gives\n#![allow(clippy::too_many_arguments)]\n\n"
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        pass
        yield 'use rapid_runtime::{Context, Handlers, Outcome, Value};\n'
    else:
        pass
        yield 'use rapid_runtime::Handlers;\n'
    l_1_loop = missing
    for l_1_h, l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'), undefined):
        _loop_vars = {}
        pass
        yield '\n/// '
        yield str(environment.getattr(l_1_h, 'title'))
        yield '\npub trait '
        yield str(environment.getattr(l_1_h, 'trait'))
        yield ': Send + Sync {\n'
        l_2_loop = missing
        for l_2_m, l_2_loop in LoopContext(environment.getattr(l_1_h, 'methods'), undefined):
            _loop_vars = {}
            pass
            if (not environment.getattr(l_2_loop, 'first')):
                pass
                yield '\n'
            for l_3_d in environment.getattr(l_2_m, 'doc'):
                _loop_vars = {}
                pass
                yield '    /// '
                yield str(l_3_d)
                yield '\n'
            l_3_d = missing
            for l_3_a in environment.getattr(l_2_m, 'params'):
                _loop_vars = {}
                pass
                yield '    /// - '
                yield str(environment.getattr(l_3_a, 'doc'))
                yield '\n'
            l_3_a = missing
            yield '    fn '
            yield str(environment.getattr(l_2_m, 'name'))
            yield '(&self, ctx: &Context'
            for l_3_a in environment.getattr(l_2_m, 'params'):
                _loop_vars = {}
                pass
                yield ', '
                yield str(environment.getattr(l_3_a, 'name'))
                yield ': '
                yield str(environment.getattr(l_3_a, 'rtype'))
            l_3_a = missing
            yield ') -> Outcome;\n'
        l_2_loop = l_2_m = missing
        yield '}\n'
    l_1_loop = l_1_h = missing
    yield "\n/// Every subsystem type's handlers (make_handlers() in handlers.rs builds it).\npub struct HandlerSet {\n"
    for l_1_h in environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        _loop_vars = {}
        pass
        yield '    pub '
        yield str(environment.getattr(l_1_h, 'member'))
        yield ': ::std::boxed::Box<dyn '
        yield str(environment.getattr(l_1_h, 'trait'))
        yield '>,\n'
    l_1_h = missing
    yield '}\n\n'
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'):
        pass
        yield '/// An argument as its declared type (the manager checked it before the handler runs).\nmacro_rules! arg {\n    ($ctx:expr, $i:expr, String) => {\n        match $ctx.args().get($i) {\n            Some(Value::String(x)) => x.as_str(),\n            _ => return Outcome::Failed(::std::format!("argument {} is not as declared", $i + 1)),\n        }\n    };\n    ($ctx:expr, $i:expr, $variant:ident) => {\n        match $ctx.args().get($i) {\n            Some(Value::$variant(x)) => *x,\n            _ => return Outcome::Failed(::std::format!("argument {} is not as declared", $i + 1)),\n        }\n    };\n}\n\nimpl Handlers for HandlerSet {\n    fn execute(&self, ctx: &Context) -> Outcome {\n        match (ctx.type_name(), ctx.command()) {\n'
        l_1_loop = missing
        for l_1_h, l_1_loop in LoopContext(environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'handlers'), undefined):
            _loop_vars = {}
            pass
            l_2_loop = missing
            for l_2_m, l_2_loop in LoopContext(environment.getattr(l_1_h, 'methods'), undefined):
                _loop_vars = {}
                pass
                yield '            ('
                yield str(environment.getattr(l_1_h, 'type'))
                yield ', '
                yield str(environment.getattr(l_2_m, 'command'))
                yield ') => self.'
                yield str(environment.getattr(l_1_h, 'member'))
                yield '.'
                yield str(environment.getattr(l_2_m, 'name'))
                yield '(ctx'
                l_3_loop = missing
                for l_3_a, l_3_loop in LoopContext(environment.getattr(l_2_m, 'params'), undefined):
                    _loop_vars = {}
                    pass
                    yield ', arg!(ctx, '
                    yield str(environment.getattr(l_3_loop, 'index0'))
                    yield ', '
                    yield str(environment.getattr(l_3_a, 'variant'))
                    yield ')'
                l_3_loop = l_3_a = missing
                yield '),\n'
            l_2_loop = l_2_m = missing
        l_1_loop = l_1_h = missing
        yield '            _ => Outcome::NotImplemented,\n        }\n    }\n}\n'
    else:
        pass
        yield "\n// (the asset takes no commands of its own: every one is the runtime's)\nimpl Handlers for HandlerSet {}\n"
    if environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams'):
        pass
        l_0_st = environment.getattr((undefined(name='v') if l_0_v is missing else l_0_v), 'streams')
        context.vars['st'] = l_0_st
        context.exported_vars.add('st')
        yield '\n// ---- setpoint streams (docs/realtime.md) ---------------------------------------------------\n\nuse ::std::sync::Arc;\n\nuse rapid_dds::bridge::Streams as StreamGlue;\n'
        if environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            pass
            yield 'use rapid_dds::stream::{Hooks, OutputStream, SampleGuard, StreamSet};\n'
        else:
            pass
            yield 'use rapid_dds::stream::{Hooks, StreamSet};\n'
        yield 'use rapid_dds::stream_sim::{Fill, SimStreams};\npub use rapid_runtime::stream::{LossAction, StreamSpec, StreamState};\nuse '
        yield str(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'crate'))
        yield "::cdr::{self, Cdr};\n\n/// The asset's setpoint streams (docs/realtime.md), read outside the command queue with\n/// DEADLINE and LIVELINESS QoS. Each input stream's method is called for every finite sample\n/// (a sample with a NaN or an infinity never reaches it) on Cyclone DDS's receive thread:\n/// keep it short and lock-free (copy the setpoint where the control loop reads it). The\n/// runtime watches the deadline: on a loss it runs the declared action (stop: "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '()\n/// is your cue to bring the driven joints to rest, and Mobility/stopAllMotion goes through\n/// the command manager when the asset has Mobility; hold: keep the last setpoint), sends a\n/// TextMessage and reports the state in AgentState. Every method has a default body: a\n/// handlers.rs written before a stream was declared still compiles. Give yours to the bridge\n/// with `HandlerSet {..}.with_streams(..)` in make_handlers(). Under --simulate the simulated\n/// robot takes the samples instead and writes the output streams.\npub trait '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'trait'))
        yield ': Send + Sync {\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            for l_2_d in environment.getattr(l_1_s, 'doc'):
                _loop_vars = {}
                pass
                yield '    /// '
                yield str(l_2_d)
                yield '\n'
            l_2_d = missing
            yield '    fn '
            yield str(environment.getattr(l_1_s, 'method'))
            yield '(&self, sample: &'
            yield str(environment.getattr(l_1_s, 'type'))
            yield ') {\n        let _ = sample;\n    }\n\n'
        l_1_s = missing
        yield "    /// A stream with on_loss stop or hold changed state: lost (the declared action is being\n    /// taken) or active (first sample, recovered). Runs on the runtime's reporting thread.\n    /// Not called for on_loss none: the runtime only reports those.\n    fn "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield "(&self, stream: &StreamSpec, state: StreamState) {\n        let _ = (stream, state);\n    }\n\n    /// Your agent values: the runtime publishes AgentState with the streams' state keys and\n    /// these (the others: their declared defaults) at the agent telemetry's rate.\n    fn "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'values_hook'))
        yield "(&self) -> ::std::vec::Vec<(::std::string::String, rapid_runtime::Value)> {\n        ::std::vec::Vec::new()\n    }\n}\n\n/// The asset's streams, by index.\npub const STREAMS: &[StreamSpec] = &[\n"
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'streams'):
            _loop_vars = {}
            pass
            yield '    '
            yield str(environment.getattr(l_1_s, 'spec'))
            yield ',\n'
        l_1_s = missing
        yield '];\n\n/// What the bridge runs: the command handlers and, when given, the stream callbacks.\n/// make_handlers() returns either this or a bare HandlerSet (no callbacks: samples are\n/// counted and watched only).\npub struct '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' {\n    pub handlers: HandlerSet,\n    pub streams: ::core::option::Option<Arc<dyn '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'trait'))
        yield ">>,\n}\n\nimpl HandlerSet {\n    /// These handlers with `streams` taking the input streams' samples.\n    pub fn with_streams(self, streams: impl "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'trait'))
        yield " + 'static) -> "
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' {\n        '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' { handlers: self, streams: ::core::option::Option::Some(Arc::new(streams)) }\n    }\n}\n\nimpl ::core::convert::From<HandlerSet> for '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' {\n    fn from(handlers: HandlerSet) -> Self {\n        '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' { handlers, streams: ::core::option::Option::None }\n    }\n}\n'
        l_1_loop = missing
        for l_1_s, l_1_loop in LoopContext(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'), undefined):
            _loop_vars = {}
            pass
            yield '\nstatic '
            yield str(environment.getattr(l_1_s, 'static'))
            yield ': OutputStream<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '> = OutputStream::new(encode::<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield '>, |s, name, stamp| header_of(&mut s.hdr, name, stamp));\n\n'
            l_2_loop = missing
            for l_2_d, l_2_loop in LoopContext(environment.getattr(l_1_s, 'doc'), undefined):
                _loop_vars = {}
                pass
                yield '/// '
                if environment.getattr(l_2_loop, 'first'):
                    pass
                    yield 'Output stream '
                yield str(l_2_d)
                yield '\n'
            l_2_loop = l_2_d = missing
            yield '///\n/// The one sample, to fill in place (kept for the whole run: its sequences keep their\n/// capacity); drop it, or call its send(), before '
            yield str(environment.getattr(l_1_s, 'send_fn'))
            yield '().\npub fn '
            yield str(environment.getattr(l_1_s, 'sample_fn'))
            yield "() -> SampleGuard<'static, "
            yield str(environment.getattr(l_1_s, 'type'))
            yield '> {\n    '
            yield str(environment.getattr(l_1_s, 'static'))
            yield '.sample()\n}\n\n/// Stamps hdr.timeStamp and writes '
            yield str(environment.getattr(l_1_s, 'sample_fn'))
            yield "()'s sample; false before the bridge\n/// started or after it stopped, or when Cyclone DDS refused it.\npub fn "
            yield str(environment.getattr(l_1_s, 'send_fn'))
            yield '() -> bool {\n    '
            yield str(environment.getattr(l_1_s, 'static'))
            yield '.send()\n}\n'
        l_1_loop = l_1_s = missing
        yield '\nfn decode<T: Cdr>(bytes: &[u8], into: &mut T) -> ::core::result::Result<(), ::std::string::String> {\n    cdr::deserialize_into(bytes, into).map_err(|e| e.to_string())\n}\n'
        if environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            pass
            yield "\nfn encode<T: Cdr>(v: &T, into: &mut ::std::vec::Vec<u8>) -> ::core::result::Result<(), ::std::string::String> {\n    cdr::serialize_into(v, cdr::Endianness::Little, into).map_err(|e| e.to_string())\n}\n\n/// An output sample's header: the asset's names (when given), the time (when not 0).\nfn header_of(hdr: &mut "
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::Header, name: &str, stamp: i64) {\n    if !name.is_empty() {\n        hdr.src_name = name.into();\n        hdr.asset_name = name.into();\n    }\n    if stamp != 0 {\n        hdr.time_stamp = stamp;\n    }\n}\n'
        if ('position' in context.call(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'kinds'), inputs=True)):
            pass
            yield "\n/// Every float of a PositionSample finite (its values' too).\nfn finite_position(s: &"
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::PositionSample) -> bool {\n    use rapid_dds::stream::{finite_f32, finite_f64};\n    finite_f64(&s.pose.xyz)\n        && finite_f32(&s.pose.rot)\n        && finite_f64(&s.velocity.xyz)\n        && finite_f32(&s.velocity.rot)\n        && s.values.iter().all(|v| match v {\n            '
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::ParameterUnion::D(x) => x.is_finite(),\n            '
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::ParameterUnion::F(x) => x.is_finite(),\n            '
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::ParameterUnion::Vec3d(x) => finite_f64(x),\n            '
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::ParameterUnion::Mat33f(x) => finite_f32(x),\n            _ => true,\n        })\n}\n'
        if ('joint' in context.call(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'kinds'), inputs=True)):
            pass
            yield "\n/// Every float of a JointSample finite (its auxFloat values' too).\nfn finite_joint(s: &"
            yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'rapid'))
            yield '::JointSample) -> bool {\n    use rapid_dds::stream::finite_f32;\n    [&s.angle_pos, &s.angle_vel, &s.angle_acc, &s.current, &s.torque, &s.temperature].iter().all(|v| finite_f32(v))\n        && s.aux_float.iter().all(|a| finite_f32(&a.values))\n}\n'
        if ('other' in context.call(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'kinds'), inputs=True)):
            pass
            yield '\n/// Another message type: handed on as it is (its handler checks what it uses).\nfn finite_any<T>(_: &T) -> bool {\n    true\n}\n'
        yield '\n/// The glue: the handlers for the command manager, the streams for rapid_dds::bridge (from\n/// what make_handlers() returns: a HandlerSet, or one with_streams).\npub fn stream_glue(d: impl ::core::convert::Into<'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield '>) -> (Arc<dyn rapid_runtime::Handlers>, StreamGlue) {\n    let d: '
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'dispatch'))
        yield ' = d.into();\n    let user = d.streams;\n    let real = {\n        let user = user.clone();\n        ::std::boxed::Box::new(move |set: &mut StreamSet| -> ::core::result::Result<(), rapid_dds::dds::DdsError> {\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '            {\n                let user = user.clone();\n                set.read::<'
            yield str(environment.getattr(l_1_s, 'type'))
            yield ', _>('
            yield str(environment.getattr(l_1_s, 'index'))
            yield ', decode, finite_'
            yield str((environment.getattr(l_1_s, 'kind') if (environment.getattr(l_1_s, 'kind') != 'other') else 'any'))
            yield ', move |s| {\n                    if let ::core::option::Option::Some(u) = &user {\n                        u.'
            yield str(environment.getattr(l_1_s, 'method'))
            yield '(s);\n                    }\n                })?;\n            }\n'
        l_1_s = missing
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            _loop_vars = {}
            pass
            yield '            set.output('
            yield str(environment.getattr(l_1_s, 'index'))
            yield ', &'
            yield str(environment.getattr(l_1_s, 'static'))
            yield ')?;\n'
        l_1_s = missing
        yield '            let _ = (&user, &set);\n            ::core::result::Result::Ok(())\n        })\n    };\n    let sim = ::std::boxed::Box::new(\n        move |set: &mut StreamSet, sim: &Arc<SimStreams>| -> ::core::result::Result<::std::vec::Vec<(f64, Fill)>, rapid_dds::dds::DdsError> {\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'inputs'):
            _loop_vars = {}
            pass
            yield '            {\n                let sim = sim.clone();\n'
            if (environment.getattr(l_1_s, 'kind') == 'position'):
                pass
                yield '                set.read::<'
                yield str(environment.getattr(l_1_s, 'type'))
                yield ', _>('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', decode, finite_position, move |s| sim.position('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', s.pose.xyz))?;\n'
            elif (environment.getattr(l_1_s, 'kind') == 'joint'):
                pass
                yield '                set.read::<'
                yield str(environment.getattr(l_1_s, 'type'))
                yield ', _>('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', decode, finite_joint, move |s| sim.joints('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', &s.angle_pos))?;\n'
            else:
                pass
                yield '                set.read::<'
                yield str(environment.getattr(l_1_s, 'type'))
                yield ', _>('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', decode, finite_any, move |_| {\n                    let _ = &sim;\n                })?;\n'
            yield '            }\n'
        l_1_s = missing
        yield '            #[allow(unused_mut)]\n            let mut fills: ::std::vec::Vec<(f64, Fill)> = ::std::vec::Vec::new();\n'
        for l_1_s in environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'outputs'):
            _loop_vars = {}
            pass
            yield '            set.output('
            yield str(environment.getattr(l_1_s, 'index'))
            yield ', &'
            yield str(environment.getattr(l_1_s, 'static'))
            yield ')?;\n            fills.push(('
            yield str(environment.getattr(l_1_s, 'period'))
            yield ', ::std::boxed::Box::new(|sim: &SimStreams, t: f64| {\n                let mut s = '
            yield str(environment.getattr(l_1_s, 'static'))
            yield '.sample();\n'
            if (environment.getattr(l_1_s, 'kind') == 'position'):
                pass
                yield '                let (xyz, rot) = sim.pose_at('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', t);\n                s.pose.xyz = xyz;\n                s.pose.rot = rot;\n'
            elif (environment.getattr(l_1_s, 'kind') == 'joint'):
                pass
                yield '                sim.joints_at('
                yield str(environment.getattr(l_1_s, 'index'))
                yield ', t, &mut s.angle_pos);\n'
            else:
                pass
                yield '                let _ = (sim, t);\n'
            yield '                s.send();\n            })));\n'
        l_1_s = missing
        yield '            let _ = (sim, &set);\n            ::core::result::Result::Ok(fills)\n        },\n    );\n    let hooks = Hooks {\n        on_state: user.clone().map(|u| {\n            ::std::boxed::Box::new(move |s: &StreamSpec, state: StreamState| u.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'state_hook'))
        yield '(s, state))\n                as rapid_dds::stream::StateHook\n        }),\n        agent_values: user.map(|u| {\n            ::std::boxed::Box::new(move || u.'
        yield str(environment.getattr((undefined(name='st') if l_0_st is missing else l_0_st), 'values_hook'))
        yield '())\n                as rapid_dds::stream::ValuesHook\n        }),\n        periodic_agent: true,\n    };\n    (Arc::new(d.handlers), StreamGlue { specs: STREAMS, real, sim, hooks })\n}\n'

blocks = {}
debug_info = '1=21&2=23&17=25&22=32&24=36&25=38&26=41&27=44&30=47&31=51&33=54&34=58&36=62&43=77&44=81&48=87&68=91&69=95&70=99&82=124&83=126&90=130&97=137&103=139&110=141&111=143&112=146&113=150&115=154&123=160&129=162&136=164&137=168&144=172&146=174&151=176&152=180&156=182&158=184&161=187&163=191&165=198&166=202&170=209&171=211&172=215&175=217&177=219&178=221&185=225&192=228&202=230&205=233&212=235&213=237&214=239&215=241&220=243&223=246&229=248&239=252&240=254&245=256&248=260&250=266&255=269&256=273&264=279&267=283&268=286&269=292&270=295&272=304&280=311&281=315&282=319&283=321&284=323&285=326&288=328&289=331&302=339&306=341'
