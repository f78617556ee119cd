# mypy: ignore-errors
# Template templates/python/_macros.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "f2fc33c1666f71df22400a2de28ae73a6fec760d58f422fbf8c39dfc2a15fca9"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_macros.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_import_line = l_0_decorators = l_0_fields = l_0_class_head = l_0_struct = l_0_bitmask = l_0_union = l_0_enum = l_0_typedef = l_0_const = l_0_declaration = missing
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
    try:
        t_3 = environment.filters['join']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'join' found.")
    pass
    def macro(l_1_i):
        t_4 = []
        if l_1_i is missing:
            l_1_i = undefined("parameter 'i' was not provided", name='i')
        pass
        if (not environment.getattr(l_1_i, 'is_from')):
            pass
            t_4.extend((
                'import ',
                str(environment.getattr(l_1_i, 'module')),
                ' as ',
                str(environment.getattr(l_1_i, 'alias')),
                '\n',
            ))
        elif environment.getattr(l_1_i, 'multiline'):
            pass
            t_4.extend((
                'from ',
                str(environment.getattr(l_1_i, 'module')),
                ' import (\n',
            ))
            for l_2_n in environment.getattr(l_1_i, 'names'):
                _loop_vars = {}
                pass
                t_4.extend((
                    '    ',
                    str(l_2_n),
                    ',\n',
                ))
            l_2_n = missing
            t_4.append(
                ')\n',
            )
        else:
            pass
            t_4.extend((
                'from ',
                str(environment.getattr(l_1_i, 'module')),
                ' import ',
                str(t_3(context.eval_ctx, environment.getattr(l_1_i, 'names'), ', ')),
                '\n',
            ))
        return concat(t_4)
    context.exported_vars.add('import_line')
    context.vars['import_line'] = l_0_import_line = Macro(environment, macro, 'import_line', ('i',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_5 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        for l_2_dec in environment.getattr(l_1_d, 'decorators'):
            _loop_vars = {}
            pass
            t_5.extend((
                str(l_2_dec),
                '\n',
            ))
        l_2_dec = missing
        return concat(t_5)
    context.exported_vars.add('decorators')
    context.vars['decorators'] = l_0_decorators = Macro(environment, macro, 'decorators', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_6 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        for l_2_mem in environment.getattr(l_1_d, 'members'):
            _loop_vars = {}
            pass
            t_6.extend((
                '    ',
                str(environment.getattr(l_2_mem, 'name')),
                ': ',
                str(environment.getattr(l_2_mem, 'type')),
                ' = ',
                str(environment.getattr(l_2_mem, 'default')),
                '\n',
            ))
            for l_3_a in environment.getattr(l_2_mem, 'annotations'):
                _loop_vars = {}
                pass
                t_6.extend((
                    '    ',
                    str(l_3_a),
                    '\n',
                ))
            l_3_a = missing
        l_2_mem = missing
        return concat(t_6)
    context.exported_vars.add('fields')
    context.vars['fields'] = l_0_fields = Macro(environment, macro, 'fields', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_7 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_7.extend((
            str(context.call((undefined(name='decorators') if l_0_decorators is missing else l_0_decorators), l_1_d)),
            'class ',
            str(environment.getattr(l_1_d, 'name')),
            '(',
            str(environment.getattr(l_1_d, 'bases')),
            '):\n    """',
            str(t_2(environment.getattr(l_1_d, 'doc'))),
            '"""\n',
        ))
        for l_2_n in environment.getattr(l_1_d, 'notes'):
            _loop_vars = {}
            pass
            t_7.extend((
                '    # ',
                str(t_1(l_2_n)),
                '\n',
            ))
        l_2_n = missing
        return concat(t_7)
    context.exported_vars.add('class_head')
    context.vars['class_head'] = l_0_class_head = Macro(environment, macro, 'class_head', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_8 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_8.extend((
            str(context.call((undefined(name='class_head') if l_0_class_head is missing else l_0_class_head), l_1_d)),
            '\n',
            str(context.call((undefined(name='fields') if l_0_fields is missing else l_0_fields), l_1_d)),
        ))
        return concat(t_8)
    context.exported_vars.add('struct')
    context.vars['struct'] = l_0_struct = Macro(environment, macro, 'struct', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_9 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_9.extend((
            str(context.call((undefined(name='class_head') if l_0_class_head is missing else l_0_class_head), l_1_d)),
            '\n',
            str(context.call((undefined(name='fields') if l_0_fields is missing else l_0_fields), l_1_d)),
        ))
        return concat(t_9)
    context.exported_vars.add('bitmask')
    context.vars['bitmask'] = l_0_bitmask = Macro(environment, macro, 'bitmask', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_10 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_10.extend((
            str(context.call((undefined(name='class_head') if l_0_class_head is missing else l_0_class_head), l_1_d)),
            '\n',
        ))
        for l_2_mem in environment.getattr(l_1_d, 'members'):
            _loop_vars = {}
            pass
            t_10.extend((
                '    ',
                str(environment.getattr(l_2_mem, 'name')),
                ': ',
                str(environment.getattr(l_2_mem, 'type')),
                '\n',
            ))
            for l_3_a in environment.getattr(l_2_mem, 'annotations'):
                _loop_vars = {}
                pass
                t_10.extend((
                    '    ',
                    str(l_3_a),
                    '\n',
                ))
            l_3_a = missing
        l_2_mem = missing
        return concat(t_10)
    context.exported_vars.add('union')
    context.vars['union'] = l_0_union = Macro(environment, macro, 'union', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_11 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_11.extend((
            str(context.call((undefined(name='class_head') if l_0_class_head is missing else l_0_class_head), l_1_d)),
            '\n',
        ))
        for l_2_mem in environment.getattr(l_1_d, 'members'):
            _loop_vars = {}
            pass
            t_11.extend((
                '    ',
                str(environment.getattr(l_2_mem, 'name')),
                ' = ',
                str(environment.getattr(l_2_mem, 'default')),
                '\n',
            ))
        l_2_mem = missing
        return concat(t_11)
    context.exported_vars.add('enum')
    context.vars['enum'] = l_0_enum = Macro(environment, macro, 'enum', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_12 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_12.extend((
            str(environment.getattr(l_1_d, 'name')),
            ' = ',
            str(environment.getattr(l_1_d, 'value')),
            '\n',
        ))
        return concat(t_12)
    context.exported_vars.add('typedef')
    context.vars['typedef'] = l_0_typedef = Macro(environment, macro, 'typedef', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_13 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_13.extend((
            str(environment.getattr(l_1_d, 'name')),
            ' = ',
            str(environment.getattr(l_1_d, 'value')),
            '\n',
        ))
        return concat(t_13)
    context.exported_vars.add('const')
    context.vars['const'] = l_0_const = Macro(environment, macro, 'const', ('d',), False, False, False, context.eval_ctx.autoescape)
    def macro(l_1_d):
        t_14 = []
        l_1_no_macro_for_this_kind = resolve('no_macro_for_this_kind')
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        if (environment.getattr(l_1_d, 'kind') == 'struct'):
            pass
            t_14.append(
                str(context.call((undefined(name='struct') if l_0_struct is missing else l_0_struct), l_1_d)),
            )
        elif (environment.getattr(l_1_d, 'kind') == 'union'):
            pass
            t_14.append(
                str(context.call((undefined(name='union') if l_0_union is missing else l_0_union), l_1_d)),
            )
        elif (environment.getattr(l_1_d, 'kind') == 'enum'):
            pass
            t_14.append(
                str(context.call((undefined(name='enum') if l_0_enum is missing else l_0_enum), l_1_d)),
            )
        elif (environment.getattr(l_1_d, 'kind') == 'bitmask'):
            pass
            t_14.append(
                str(context.call((undefined(name='bitmask') if l_0_bitmask is missing else l_0_bitmask), l_1_d)),
            )
        elif (environment.getattr(l_1_d, 'kind') == 'typedef'):
            pass
            t_14.append(
                str(context.call((undefined(name='typedef') if l_0_typedef is missing else l_0_typedef), l_1_d)),
            )
        elif (environment.getattr(l_1_d, 'kind') == 'const'):
            pass
            t_14.append(
                str(context.call((undefined(name='const') if l_0_const is missing else l_0_const), l_1_d)),
            )
        else:
            pass
            t_14.append(
                str(context.call((undefined(name='no_macro_for_this_kind') if l_1_no_macro_for_this_kind is missing else l_1_no_macro_for_this_kind), l_1_d)),
            )
        return concat(t_14)
    context.exported_vars.add('declaration')
    context.vars['declaration'] = l_0_declaration = Macro(environment, macro, 'declaration', ('d',), False, False, False, context.eval_ctx.autoescape)

blocks = {}
debug_info = '2=30&3=35&4=39&5=44&6=48&7=51&8=56&12=67&16=76&17=81&18=85&22=93&23=98&24=103&25=110&26=115&31=124&32=130&33=136&34=139&35=144&39=152&40=158&41=160&44=166&45=172&46=174&49=180&50=186&51=189&52=194&53=199&54=204&59=213&60=219&61=222&62=227&66=237&67=243&70=252&71=258&75=266&76=272'
