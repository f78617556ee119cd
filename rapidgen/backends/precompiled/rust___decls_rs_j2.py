# mypy: ignore-errors
# Template templates/rust/_decls.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "572de2b07fa9879bb706cd190272931514baf86425f4fdf1fb9d60cc2c1cb283"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_decls.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_DERIVE_SERDE = l_0_decls = missing
    try:
        t_1 = environment.filters['list']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'list' found.")
    try:
        t_2 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    try:
        t_3 = environment.filters['rust_str']
    except KeyError:
        @internalcode
        def t_3(*unused):
            raise TemplateRuntimeError("No filter named 'rust_str' found.")
    try:
        t_4 = environment.filters['selectattr']
    except KeyError:
        @internalcode
        def t_4(*unused):
            raise TemplateRuntimeError("No filter named 'selectattr' found.")
    pass
    l_0_DERIVE_SERDE = '#[cfg_attr(feature = "serde", derive(::serde::Serialize, ::serde::Deserialize))]'
    context.vars['DERIVE_SERDE'] = l_0_DERIVE_SERDE
    context.exported_vars.add('DERIVE_SERDE')
    def macro(l_1_m):
        t_5 = []
        if l_1_m is missing:
            l_1_m = undefined("parameter 'm' was not provided", name='m')
        pass
        for l_2_d in environment.getattr(l_1_m, 'decls'):
            _loop_vars = {}
            pass
            t_5.extend((
                '\n/// ',
                str(t_2(environment.getattr(l_2_d, 'doc'))),
                '\n',
            ))
            if (environment.getattr(l_2_d, 'kind') == 'typedef'):
                pass
                t_5.extend((
                    'pub type ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' = ',
                    str(environment.getattr(l_2_d, 'type')),
                    ';\n',
                ))
            elif (environment.getattr(l_2_d, 'kind') == 'const'):
                pass
                t_5.extend((
                    'pub const ',
                    str(environment.getattr(l_2_d, 'name')),
                    ': ',
                    str(environment.getattr(l_2_d, 'type')),
                    ' = ',
                    str(environment.getattr(l_2_d, 'value')),
                    ';\n',
                ))
            elif (environment.getattr(l_2_d, 'kind') == 'enum'):
                pass
                t_5.extend((
                    '#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_5.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_5.extend((
                    '#[repr(',
                    str(environment.getattr(l_2_d, 'type')),
                    ")]\n#[allow(clippy::enum_variant_names)] // the IDL's enumerator names\npub enum ",
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for (l_3_n, l_3_v, l_3_wire) in environment.getattr(l_2_d, 'variants'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '    /// ',
                        str(t_2(l_3_wire)),
                        '\n',
                    ))
                    if (l_3_n == environment.getattr(l_2_d, 'default_variant')):
                        pass
                        t_5.append(
                            '    #[default]\n',
                        )
                    if environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n):
                        pass
                        t_5.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n)),
                            '))]\n',
                        ))
                    t_5.extend((
                        '    ',
                        str(l_3_n),
                        ' = ',
                        str(l_3_v),
                        ',\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_5.extend((
                    '}\n\nimpl ',
                    str(environment.getattr(l_2_d, 'name')),
                    " {\n    /// The IDL name of the enumerator.\n    pub fn idl_name(self) -> &'static str {\n        match self {\n",
                ))
                for (l_3_n, l_3_v, l_3_wire) in environment.getattr(l_2_d, 'variants'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            Self::',
                        str(l_3_n),
                        ' => ',
                        str(t_3(l_3_wire)),
                        ',\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_5.extend((
                    '        }\n    }\n}\n\nimpl crate::cdr::Cdr for ',
                    str(environment.getattr(l_2_d, 'name')),
                    " {\n    const TYPE_NAME: &'static str = ",
                    str(environment.getattr(l_2_d, 'type_name')),
                    ';\n\n    fn encode(&self, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::EncodeError> {\n        w.put::<',
                    str(environment.getattr(l_2_d, 'type')),
                    '>(*self as ',
                    str(environment.getattr(l_2_d, 'type')),
                    ');\n        Ok(())\n    }\n\n    fn size(&self, s: &mut crate::cdr::Size) {\n        s.put::<',
                    str(environment.getattr(l_2_d, 'type')),
                    ">();\n    }\n\n    fn decode(r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<Self, crate::cdr::DecodeError> {\n        match r.get::<",
                    str(environment.getattr(l_2_d, 'type')),
                    '>()? {\n',
                ))
                for (l_3_n, l_3_v, l_3_wire) in environment.getattr(l_2_d, 'variants'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            ',
                        str(l_3_v),
                        ' => Ok(Self::',
                        str(l_3_n),
                        '),\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_5.append(
                    '            v => Err(r.error(format_args!("{v} is not a value of enum {}", Self::TYPE_NAME))),\n        }\n    }\n}\n',
                )
            elif (environment.getattr(l_2_d, 'kind') == 'struct'):
                pass
                t_5.extend((
                    '#[derive(Debug, Clone, PartialEq',
                    str((', Default' if environment.getattr(l_2_d, 'derive_default') else '')),
                    ')]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_5.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_5.extend((
                    'pub struct ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '    /// IDL `',
                        str(t_2(environment.getattr(l_3_f, 'wire'))),
                        '`\n',
                    ))
                    if environment.getattr(l_3_f, 'serde'):
                        pass
                        t_5.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getattr(l_3_f, 'serde')),
                            '))]\n',
                        ))
                    t_5.extend((
                        '    pub ',
                        str(environment.getattr(l_3_f, 'name')),
                        ': ',
                        str(environment.getattr(l_3_f, 'type')),
                        ',\n',
                    ))
                l_3_f = missing
                t_5.append(
                    '}\n',
                )
                if (not environment.getattr(l_2_d, 'derive_default')):
                    pass
                    t_5.extend((
                        '\nimpl ::core::default::Default for ',
                        str(environment.getattr(l_2_d, 'name')),
                        ' {\n    fn default() -> Self {\n        Self {\n',
                    ))
                    for l_3_f in environment.getattr(l_2_d, 'members'):
                        _loop_vars = {}
                        pass
                        t_5.extend((
                            '            ',
                            str(environment.getattr(l_3_f, 'name')),
                            ': ',
                            str(environment.getattr(l_3_f, 'default')),
                            ',\n',
                        ))
                    l_3_f = missing
                    t_5.append(
                        '        }\n    }\n}\n',
                    )
                t_5.extend((
                    '\nimpl crate::cdr::Cdr for ',
                    str(environment.getattr(l_2_d, 'name')),
                    " {\n    const TYPE_NAME: &'static str = ",
                    str(environment.getattr(l_2_d, 'type_name')),
                    ';\n\n    fn encode(&self, ',
                    str(('w' if environment.getattr(l_2_d, 'encode') else '_w')),
                    ': &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::EncodeError> {\n',
                ))
                for l_3_s in environment.getattr(l_2_d, 'encode'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '        ',
                        str(l_3_s),
                        '\n',
                    ))
                l_3_s = missing
                t_5.extend((
                    '        Ok(())\n    }\n\n    fn size(&self, ',
                    str(('s' if environment.getattr(l_2_d, 'size') else '_s')),
                    ': &mut crate::cdr::Size) {\n',
                ))
                for l_3_s in environment.getattr(l_2_d, 'size'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '        ',
                        str(l_3_s),
                        '\n',
                    ))
                l_3_s = missing
                t_5.append(
                    "    }\n\n    fn decode(r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<Self, crate::cdr::DecodeError> {\n        r.enter()?;\n        let v = Self {\n",
                )
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            ',
                        str(environment.getattr(l_3_f, 'name')),
                        ': ',
                        str(environment.getattr(l_3_f, 'decode')),
                        ',\n',
                    ))
                l_3_f = missing
                t_5.append(
                    "        };\n        r.leave();\n        Ok(v)\n    }\n\n    fn decode_into(&mut self, r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<(), crate::cdr::DecodeError> {\n        r.enter()?;\n",
                )
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '        ',
                        str(environment.getattr(l_3_f, 'decode_into')),
                        '\n',
                    ))
                l_3_f = missing
                t_5.append(
                    '        r.leave();\n        Ok(())\n    }\n',
                )
                if environment.getattr(l_2_d, 'key'):
                    pass
                    t_5.extend((
                        '\n    const KEYED: bool = true;\n    const KEY_MAX_SIZE: usize = ',
                        str(environment.getattr(l_2_d, 'key_max')),
                        ';\n\n    fn encode_key(&self, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::EncodeError> {\n',
                    ))
                    for l_3_s in environment.getattr(l_2_d, 'key'):
                        _loop_vars = {}
                        pass
                        t_5.extend((
                            '        ',
                            str(l_3_s),
                            '\n',
                        ))
                    l_3_s = missing
                    t_5.append(
                        "        Ok(())\n    }\n\n    fn transcode_key(r: &mut crate::cdr::Reader<'_>, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::DecodeError> {\n",
                    )
                    for l_3_s in environment.getattr(l_2_d, 'transcode'):
                        _loop_vars = {}
                        pass
                        t_5.extend((
                            '        ',
                            str(l_3_s),
                            '\n',
                        ))
                    l_3_s = missing
                    t_5.append(
                        '        Ok(())\n    }\n',
                    )
                t_5.extend((
                    '}\n\nimpl crate::TopicType for ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {}\n',
                ))
            elif (environment.getattr(l_2_d, 'kind') == 'union'):
                pass
                t_5.extend((
                    '/// The variant selects the branch; it holds the discriminator when one label does not imply it.\n#[derive(Debug, Clone, PartialEq)]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_5.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_5.extend((
                    "#[allow(clippy::large_enum_variant)] // the IDL's branches, as they are on the wire\npub enum ",
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for (l_3_n, l_3_fields) in environment.getattr(l_2_d, 'variant_types'):
                    _loop_vars = {}
                    pass
                    if context.call(environment.getattr(environment.getattr(l_2_d, 'variant_serde'), 'get'), l_3_n, _loop_vars=_loop_vars):
                        pass
                        t_5.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n)),
                            '))]\n',
                        ))
                    t_5.extend((
                        '    ',
                        str(l_3_n),
                        '(',
                        str(l_3_fields),
                        '),\n',
                    ))
                l_3_n = l_3_fields = missing
                t_5.extend((
                    '}\n\nimpl ::core::default::Default for ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n    fn default() -> Self {\n        ',
                    str(environment.getattr(l_2_d, 'value')),
                    '\n    }\n}\n\nimpl crate::cdr::Cdr for ',
                    str(environment.getattr(l_2_d, 'name')),
                    " {\n    const TYPE_NAME: &'static str = ",
                    str(environment.getattr(l_2_d, 'type_name')),
                    ';\n\n    fn encode(&self, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::EncodeError> {\n        match self {\n',
                ))
                for l_3_a in environment.getattr(l_2_d, 'arms'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'head')),
                        ' => {\n',
                    ))
                    if environment.getattr(l_3_a, 'check'):
                        pass
                        t_5.extend((
                            '                if ',
                            str(environment.getattr(l_3_a, 'check')),
                            ' {\n                    return Err(crate::cdr::EncodeError { message: format!("{}: discriminator {d:?} does not select ',
                            str(environment.getattr(l_3_a, 'variant')),
                            '", Self::TYPE_NAME) });\n                }\n',
                        ))
                    for l_4_s in environment.getattr(l_3_a, 'encode'):
                        _loop_vars = {}
                        pass
                        t_5.extend((
                            '                ',
                            str(l_4_s),
                            '\n',
                        ))
                    l_4_s = missing
                    t_5.append(
                        '            }\n',
                    )
                l_3_a = missing
                t_5.append(
                    '        }\n        Ok(())\n    }\n\n    fn size(&self, s: &mut crate::cdr::Size) {\n',
                )
                for l_3_x in environment.getattr(l_2_d, 'size'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '        ',
                        str(l_3_x),
                        '\n',
                    ))
                l_3_x = missing
                t_5.append(
                    '        match self {\n',
                )
                for l_3_a in environment.getattr(l_2_d, 'arms'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'size_head')),
                        ' => ',
                        str(((('{ ' + environment.getattr(l_3_a, 'size')) + ' }') if environment.getattr(l_3_a, 'size') else '{}')),
                        '\n',
                    ))
                l_3_a = missing
                t_5.extend((
                    "        }\n    }\n\n    fn decode(r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<Self, crate::cdr::DecodeError> {\n        r.enter()?;\n        let d = ",
                    str(environment.getattr(l_2_d, 'disc_decode')),
                    ';\n',
                ))
                if environment.getattr(l_2_d, 'allow_unreachable'):
                    pass
                    t_5.append(
                        '        #[allow(unreachable_patterns)]\n',
                    )
                t_5.append(
                    '        let v = match d {\n',
                )
                for l_3_a in environment.getattr(l_2_d, 'arms'):
                    _loop_vars = {}
                    pass
                    t_5.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'pattern')),
                        ' => ',
                        str(environment.getattr(l_3_a, 'build')),
                        ',\n',
                    ))
                l_3_a = missing
                t_5.append(
                    '        };\n        r.leave();\n        Ok(v)\n    }\n',
                )
                if t_1(context.eval_ctx, t_4(context, environment.getattr(l_2_d, 'arms'), 'into')):
                    pass
                    t_5.extend((
                        "\n    #[allow(unreachable_patterns)] // `_` after the only variant, or after every label\n    fn decode_into(&mut self, r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<(), crate::cdr::DecodeError> {\n        r.enter()?;\n        let d = ",
                        str(environment.getattr(l_2_d, 'disc_decode')),
                        ';\n        match d {\n',
                    ))
                    for l_3_a in environment.getattr(l_2_d, 'arms'):
                        _loop_vars = {}
                        pass
                        if environment.getattr(l_3_a, 'into'):
                            pass
                            t_5.extend((
                                '            ',
                                str(environment.getattr(l_3_a, 'pattern')),
                                ' => match self {\n                ',
                                str(environment.getattr(l_3_a, 'into_head')),
                                ' => {\n                    ',
                                str(environment.getattr(l_3_a, 'into')),
                                '\n                }\n                _ => *self = ',
                                str(environment.getattr(l_3_a, 'build')),
                                ',\n            },\n',
                            ))
                        else:
                            pass
                            t_5.extend((
                                '            ',
                                str(environment.getattr(l_3_a, 'pattern')),
                                ' => *self = ',
                                str(environment.getattr(l_3_a, 'build')),
                                ',\n',
                            ))
                    l_3_a = missing
                    t_5.append(
                        '        }\n        r.leave();\n        Ok(())\n    }\n',
                    )
                t_5.extend((
                    '}\n\nimpl crate::TopicType for ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {}\n',
                ))
        l_2_d = missing
        if environment.getattr(l_1_m, 'children'):
            pass
            t_5.append(
                '\n',
            )
            for l_2_c in environment.getattr(l_1_m, 'children'):
                _loop_vars = {}
                pass
                t_5.extend((
                    'pub mod ',
                    str(l_2_c),
                    ';\n',
                ))
            l_2_c = missing
        return concat(t_5)
    context.exported_vars.add('decls')
    context.vars['decls'] = l_0_decls = Macro(environment, macro, 'decls', ('m',), False, False, False, context.eval_ctx.autoescape)

blocks = {}
debug_info = '1=36&2=39&3=44&5=49&6=52&7=56&8=61&9=65&10=72&12=76&13=79&14=83&16=88&18=90&19=93&20=98&21=101&24=106&25=110&27=115&31=123&35=126&36=131&42=139&43=141&46=143&51=147&55=149&56=152&57=157&63=166&64=170&65=172&66=175&67=179&69=184&70=187&71=192&72=195&73=199&75=204&78=213&80=217&83=220&84=225&91=236&92=238&94=240&95=243&96=248&101=254&102=257&103=262&110=269&111=274&120=283&121=288&126=295&129=299&132=302&133=307&139=314&140=319&147=328&148=331&151=335&152=338&153=342&156=347&157=350&158=353&159=357&161=362&165=370&167=372&171=374&172=376&176=379&177=384&178=387&179=391&180=393&183=396&184=401&193=412&194=417&197=424&198=429&205=437&206=440&210=448&211=453&217=462&222=466&224=469&225=472&226=476&227=478&228=480&230=482&233=489&243=500&246=504&248=509&249=514'
