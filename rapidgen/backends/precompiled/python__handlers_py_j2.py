# mypy: ignore-errors
# Template templates/python/handlers.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "b43a71454d8ed42ded6893711037cbe45cdf6790bf1ad6fc03951f5483b148bf"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'handlers.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_asset = resolve('asset')
    l_0_package = resolve('package')
    l_0_methods = resolve('methods')
    try:
        t_1 = environment.filters['comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'comment' found.")
    try:
        t_2 = environment.filters['docstring']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'docstring' found.")
    pass
    yield '# Handlers of asset '
    yield str(t_1((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ': written once by rapidgen, yours to edit.\n# Regeneration never touches this file (delete it to get fresh stubs).\n"""Command handlers of '
    yield str(t_2((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ', called by the rapid_runtime bridge\n(`python -m '
    yield str((undefined(name='package') if l_0_package is missing else l_0_package))
    yield '.bridge`).\n\nOne method per command, with the command\'s arguments by name. Return normally for\nCOMPLETED/OK (a returned string becomes Ack.message, at most 127 bytes); raise\nCommandFailed("why") for COMPLETED/EXEC_FAILED. A method runs in its own thread: it may\nrun long, report progress with ctx.progress("..."), and should stop when\nctx.cancelled is set (ctx.sleep(s) returns False then). Arguments were already checked\nagainst the descriptor (types, ranges, allowed values). The standard Admin, Queue and\nAccessControl commands are answered by the runtime.\n"""\n\nfrom __future__ import annotations\n\nfrom rapid_runtime.handlers import CommandContext, CommandFailed, Handlers as _Base\n\n\nclass Handlers(_Base):\n'
    t_3 = 1
    for l_1_h in (undefined(name='methods') if l_0_methods is missing else l_0_methods):
        _loop_vars = {}
        pass
        yield '\n    def '
        yield str(environment.getattr(l_1_h, 'method'))
        yield '(self, ctx: CommandContext'
        for l_2_p in environment.getattr(l_1_h, 'params'):
            _loop_vars = {}
            pass
            yield ', '
            yield str(environment.getattr(l_2_p, 'arg'))
            yield ': '
            yield str(environment.getattr(l_2_p, 'pytype'))
        l_2_p = missing
        yield ') -> str | None:\n        """'
        yield str(t_2(environment.getattr(l_1_h, 'title')))
        yield '\n\n        '
        yield str(t_2(environment.getattr(l_1_h, 'where')))
        yield '\n'
        if environment.getattr(l_1_h, 'params'):
            pass
            yield '\n'
            for l_2_p in environment.getattr(l_1_h, 'params'):
                _loop_vars = {}
                pass
                yield '        '
                yield str(t_2(environment.getattr(l_2_p, 'doc')))
                yield '\n'
            l_2_p = missing
        if environment.getattr(l_1_h, 'stop_first'):
            pass
            yield '\n        The runtime has already canceled every Mobility command; stop the hardware here.\n'
        yield '        """\n        raise CommandFailed("not implemented")\n'
        t_3 = 0
    l_1_h = missing
    if t_3:
        pass
        yield '    """This asset takes no commands of its own."""\n'

blocks = {}
debug_info = '1=27&3=29&4=31&21=34&23=38&24=49&26=51&27=53&29=56&30=60&33=63'
