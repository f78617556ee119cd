# mypy: ignore-errors
# Template templates/python/asset_tables.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "ce485f537152f3c3d44c6b05a50d1b65a160028d05b3b6c7dcbd66c6a6dff48d"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'asset_tables.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    l_0_asset = resolve('asset')
    l_0_body = resolve('body')
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
    yield '# '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n"""Asset '
    yield str(t_2((undefined(name='asset') if l_0_asset is missing else l_0_asset)))
    yield ' as data: what the rapid_runtime library serves.\n\nFORMAT        the tables\' format version (rapid_runtime.tables.FORMAT)\nASSET         name, kind, description, tags, DDS domain and partition\nSUBSYSTEMS    subsystem -> subsystem type, in CommandConfig order\nCOMMANDS      subsystem type -> command -> handler method, flags, parameters (in the\n              order arguments are sent: name, handler keyword, DataType, unit, range,\n              allowed values, default) and, when the descriptor declares it, the\n              handler\'s stop bound stop_timeout_ms [ms]\nACCESS        the command-source allow-list (None: any source may command)\nCONFIGS       topic -> the computed config (IDL member names; hdr is set at run time)\nPUBLICATIONS  every topic the asset publishes: role, type, QoS profile, rate [Hz]\nTELEMETRY     the descriptor\'s telemetry entries, with their value keys and joints\n"""\n\n'
    yield str((undefined(name='body') if l_0_body is missing else l_0_body))
    yield '\n'

blocks = {}
debug_info = '1=27&2=29&17=31'
