# mypy: ignore-errors
# Template templates/rust/bridge/dispatch.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "b247b6ed4c034908e55203dd44368c2d68150ce3b4c8c51601b2763017d0f0a5"
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

blocks = {}
debug_info = '1=20&2=22&17=24&22=31&24=35&25=37&26=40&27=43&30=46&31=50&33=53&34=57&36=61&43=76&44=80&48=86&68=90&69=94&70=98'
