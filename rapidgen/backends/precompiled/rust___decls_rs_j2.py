# mypy: ignore-errors
# Template templates/rust/_decls.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "fcc5c8ab7d4d6af0239e6b890e3b44877969f92fa3c32794af0e75410ea28d0d"
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
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    try:
        t_2 = environment.filters['rust_str']
    except KeyError:
        @internalcode
        def t_2(*unused):
            raise TemplateRuntimeError("No filter named 'rust_str' found.")
    pass
    l_0_DERIVE_SERDE = '#[cfg_attr(feature = "serde", derive(::serde::Serialize, ::serde::Deserialize))]'
    context.vars['DERIVE_SERDE'] = l_0_DERIVE_SERDE
    context.exported_vars.add('DERIVE_SERDE')
    def macro(l_1_m):
        t_3 = []
        if l_1_m is missing:
            l_1_m = undefined("parameter 'm' was not provided", name='m')
        pass
        for l_2_d in environment.getattr(l_1_m, 'decls'):
            _loop_vars = {}
            pass
            t_3.extend((
                '\n/// ',
                str(t_1(environment.getattr(l_2_d, 'doc'))),
                '\n',
            ))
            if (environment.getattr(l_2_d, 'kind') == 'typedef'):
                pass
                t_3.extend((
                    'pub type ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' = ',
                    str(environment.getattr(l_2_d, 'type')),
                    ';\n',
                ))
            elif (environment.getattr(l_2_d, 'kind') == 'const'):
                pass
                t_3.extend((
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
                t_3.extend((
                    '#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_3.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_3.extend((
                    '#[repr(',
                    str(environment.getattr(l_2_d, 'type')),
                    ")]\n#[allow(clippy::enum_variant_names)] // the IDL's enumerator names\npub enum ",
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for (l_3_n, l_3_v, l_3_wire) in environment.getattr(l_2_d, 'variants'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '    /// ',
                        str(t_1(l_3_wire)),
                        '\n',
                    ))
                    if (l_3_n == environment.getattr(l_2_d, 'default_variant')):
                        pass
                        t_3.append(
                            '    #[default]\n',
                        )
                    if environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n):
                        pass
                        t_3.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n)),
                            '))]\n',
                        ))
                    t_3.extend((
                        '    ',
                        str(l_3_n),
                        ' = ',
                        str(l_3_v),
                        ',\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_3.extend((
                    '}\n\nimpl ',
                    str(environment.getattr(l_2_d, 'name')),
                    " {\n    /// The IDL name of the enumerator.\n    pub fn idl_name(self) -> &'static str {\n        match self {\n",
                ))
                for (l_3_n, l_3_v, l_3_wire) in environment.getattr(l_2_d, 'variants'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '            Self::',
                        str(l_3_n),
                        ' => ',
                        str(t_2(l_3_wire)),
                        ',\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_3.extend((
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
                    t_3.extend((
                        '            ',
                        str(l_3_v),
                        ' => Ok(Self::',
                        str(l_3_n),
                        '),\n',
                    ))
                l_3_n = l_3_v = l_3_wire = missing
                t_3.append(
                    '            v => Err(r.error(format_args!("{v} is not a value of enum {}", Self::TYPE_NAME))),\n        }\n    }\n}\n',
                )
            elif (environment.getattr(l_2_d, 'kind') == 'struct'):
                pass
                t_3.extend((
                    '#[derive(Debug, Clone, PartialEq',
                    str((', Default' if environment.getattr(l_2_d, 'derive_default') else '')),
                    ')]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_3.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_3.extend((
                    'pub struct ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '    /// IDL `',
                        str(t_1(environment.getattr(l_3_f, 'wire'))),
                        '`\n',
                    ))
                    if environment.getattr(l_3_f, 'serde'):
                        pass
                        t_3.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getattr(l_3_f, 'serde')),
                            '))]\n',
                        ))
                    t_3.extend((
                        '    pub ',
                        str(environment.getattr(l_3_f, 'name')),
                        ': ',
                        str(environment.getattr(l_3_f, 'type')),
                        ',\n',
                    ))
                l_3_f = missing
                t_3.append(
                    '}\n',
                )
                if (not environment.getattr(l_2_d, 'derive_default')):
                    pass
                    t_3.extend((
                        '\nimpl ::core::default::Default for ',
                        str(environment.getattr(l_2_d, 'name')),
                        ' {\n    fn default() -> Self {\n        Self {\n',
                    ))
                    for l_3_f in environment.getattr(l_2_d, 'members'):
                        _loop_vars = {}
                        pass
                        t_3.extend((
                            '            ',
                            str(environment.getattr(l_3_f, 'name')),
                            ': ',
                            str(environment.getattr(l_3_f, 'default')),
                            ',\n',
                        ))
                    l_3_f = missing
                    t_3.append(
                        '        }\n    }\n}\n',
                    )
                t_3.extend((
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
                    t_3.extend((
                        '        ',
                        str(l_3_s),
                        '\n',
                    ))
                l_3_s = missing
                t_3.extend((
                    '        Ok(())\n    }\n\n    fn size(&self, ',
                    str(('s' if environment.getattr(l_2_d, 'size') else '_s')),
                    ': &mut crate::cdr::Size) {\n',
                ))
                for l_3_s in environment.getattr(l_2_d, 'size'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '        ',
                        str(l_3_s),
                        '\n',
                    ))
                l_3_s = missing
                t_3.append(
                    "    }\n\n    fn decode(r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<Self, crate::cdr::DecodeError> {\n        r.enter()?;\n        let v = Self {\n",
                )
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '            ',
                        str(environment.getattr(l_3_f, 'name')),
                        ': ',
                        str(environment.getattr(l_3_f, 'decode')),
                        ',\n',
                    ))
                l_3_f = missing
                t_3.append(
                    "        };\n        r.leave();\n        Ok(v)\n    }\n\n    fn decode_into(&mut self, r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<(), crate::cdr::DecodeError> {\n        r.enter()?;\n",
                )
                for l_3_f in environment.getattr(l_2_d, 'members'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '        ',
                        str(environment.getattr(l_3_f, 'decode_into')),
                        '\n',
                    ))
                l_3_f = missing
                t_3.append(
                    '        r.leave();\n        Ok(())\n    }\n',
                )
                if environment.getattr(l_2_d, 'key'):
                    pass
                    t_3.extend((
                        '\n    const KEYED: bool = true;\n    const KEY_MAX_SIZE: usize = ',
                        str(environment.getattr(l_2_d, 'key_max')),
                        ';\n\n    fn encode_key(&self, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::EncodeError> {\n',
                    ))
                    for l_3_s in environment.getattr(l_2_d, 'key'):
                        _loop_vars = {}
                        pass
                        t_3.extend((
                            '        ',
                            str(l_3_s),
                            '\n',
                        ))
                    l_3_s = missing
                    t_3.append(
                        "        Ok(())\n    }\n\n    fn transcode_key(r: &mut crate::cdr::Reader<'_>, w: &mut crate::cdr::Writer) -> ::core::result::Result<(), crate::cdr::DecodeError> {\n",
                    )
                    for l_3_s in environment.getattr(l_2_d, 'transcode'):
                        _loop_vars = {}
                        pass
                        t_3.extend((
                            '        ',
                            str(l_3_s),
                            '\n',
                        ))
                    l_3_s = missing
                    t_3.append(
                        '        Ok(())\n    }\n',
                    )
                t_3.extend((
                    '}\n\nimpl crate::TopicType for ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {}\n',
                ))
            elif (environment.getattr(l_2_d, 'kind') == 'union'):
                pass
                t_3.extend((
                    '/// The variant selects the branch; it holds the discriminator when one label does not imply it.\n#[derive(Debug, Clone, PartialEq)]\n',
                    str((undefined(name='DERIVE_SERDE') if l_0_DERIVE_SERDE is missing else l_0_DERIVE_SERDE)),
                    '\n',
                ))
                if environment.getattr(l_2_d, 'serde'):
                    pass
                    t_3.extend((
                        '#[cfg_attr(feature = "serde", serde(',
                        str(environment.getattr(l_2_d, 'serde')),
                        '))]\n',
                    ))
                t_3.extend((
                    "#[allow(clippy::large_enum_variant)] // the IDL's branches, as they are on the wire\npub enum ",
                    str(environment.getattr(l_2_d, 'name')),
                    ' {\n',
                ))
                for (l_3_n, l_3_fields) in environment.getattr(l_2_d, 'variant_types'):
                    _loop_vars = {}
                    pass
                    if context.call(environment.getattr(environment.getattr(l_2_d, 'variant_serde'), 'get'), l_3_n, _loop_vars=_loop_vars):
                        pass
                        t_3.extend((
                            '    #[cfg_attr(feature = "serde", serde(',
                            str(environment.getitem(environment.getattr(l_2_d, 'variant_serde'), l_3_n)),
                            '))]\n',
                        ))
                    t_3.extend((
                        '    ',
                        str(l_3_n),
                        '(',
                        str(l_3_fields),
                        '),\n',
                    ))
                l_3_n = l_3_fields = missing
                t_3.extend((
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
                    t_3.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'head')),
                        ' => {\n',
                    ))
                    if environment.getattr(l_3_a, 'check'):
                        pass
                        t_3.extend((
                            '                if ',
                            str(environment.getattr(l_3_a, 'check')),
                            ' {\n                    return Err(crate::cdr::EncodeError { message: format!("{}: discriminator {d:?} does not select ',
                            str(environment.getattr(l_3_a, 'variant')),
                            '", Self::TYPE_NAME) });\n                }\n',
                        ))
                    for l_4_s in environment.getattr(l_3_a, 'encode'):
                        _loop_vars = {}
                        pass
                        t_3.extend((
                            '                ',
                            str(l_4_s),
                            '\n',
                        ))
                    l_4_s = missing
                    t_3.append(
                        '            }\n',
                    )
                l_3_a = missing
                t_3.append(
                    '        }\n        Ok(())\n    }\n\n    fn size(&self, s: &mut crate::cdr::Size) {\n',
                )
                for l_3_x in environment.getattr(l_2_d, 'size'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '        ',
                        str(l_3_x),
                        '\n',
                    ))
                l_3_x = missing
                t_3.append(
                    '        match self {\n',
                )
                for l_3_a in environment.getattr(l_2_d, 'arms'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'size_head')),
                        ' => ',
                        str(((('{ ' + environment.getattr(l_3_a, 'size')) + ' }') if environment.getattr(l_3_a, 'size') else '{}')),
                        '\n',
                    ))
                l_3_a = missing
                t_3.extend((
                    "        }\n    }\n\n    fn decode(r: &mut crate::cdr::Reader<'_>) -> ::core::result::Result<Self, crate::cdr::DecodeError> {\n        r.enter()?;\n        let d = ",
                    str(environment.getattr(l_2_d, 'disc_decode')),
                    ';\n',
                ))
                if environment.getattr(l_2_d, 'allow_unreachable'):
                    pass
                    t_3.append(
                        '        #[allow(unreachable_patterns)]\n',
                    )
                t_3.append(
                    '        let v = match d {\n',
                )
                for l_3_a in environment.getattr(l_2_d, 'arms'):
                    _loop_vars = {}
                    pass
                    t_3.extend((
                        '            ',
                        str(environment.getattr(l_3_a, 'pattern')),
                        ' => ',
                        str(environment.getattr(l_3_a, 'build')),
                        ',\n',
                    ))
                l_3_a = missing
                t_3.extend((
                    '        };\n        r.leave();\n        Ok(v)\n    }\n}\n\nimpl crate::TopicType for ',
                    str(environment.getattr(l_2_d, 'name')),
                    ' {}\n',
                ))
        l_2_d = missing
        if environment.getattr(l_1_m, 'children'):
            pass
            t_3.append(
                '\n',
            )
            for l_2_c in environment.getattr(l_1_m, 'children'):
                _loop_vars = {}
                pass
                t_3.extend((
                    'pub mod ',
                    str(l_2_c),
                    ';\n',
                ))
            l_2_c = missing
        return concat(t_3)
    context.exported_vars.add('decls')
    context.vars['decls'] = l_0_decls = Macro(environment, macro, 'decls', ('m',), False, False, False, context.eval_ctx.autoescape)

blocks = {}
debug_info = '1=24&2=27&3=32&5=37&6=40&7=44&8=49&9=53&10=60&12=64&13=67&14=71&16=76&18=78&19=81&20=86&21=89&24=94&25=98&27=103&31=111&35=114&36=119&42=127&43=129&46=131&51=135&55=137&56=140&57=145&63=154&64=158&65=160&66=163&67=167&69=172&70=175&71=180&72=183&73=187&75=192&78=201&80=205&83=208&84=213&91=224&92=226&94=228&95=231&96=236&101=242&102=245&103=250&110=257&111=262&120=271&121=276&126=283&129=287&132=290&133=295&139=302&140=307&147=316&148=319&151=323&152=326&153=330&156=335&157=338&158=341&159=345&161=350&165=358&167=360&171=362&172=364&176=367&177=372&178=375&179=379&180=381&183=384&184=389&193=400&194=405&197=412&198=417&205=425&206=428&210=436&211=441&219=449&222=453&224=458&225=463'
