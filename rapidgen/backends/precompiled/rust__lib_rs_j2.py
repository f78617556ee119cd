# mypy: ignore-errors
# Template templates/rust/lib.rs.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "bb694d68ce8b969594ef0f339b750c687be4c1b82d3c8bb56da7f2b19f49ebe8"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'lib.rs.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_c = resolve('c')
    l_0_asset = resolve('asset')
    l_0_m = resolve('m')
    l_0_decls = missing
    try:
        t_1 = environment.filters['rust_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'rust_comment' found.")
    pass
    included_template = environment.get_template('_decls.rs.j2', 'lib.rs.j2')._get_default_module(context)
    l_0_decls = getattr(included_template, 'decls', missing)
    if l_0_decls is missing:
        l_0_decls = undefined(f"the template {included_template.__name__!r} (imported on line 1 in 'lib.rs.j2') does not export the requested name 'decls'", name='decls')
    context.vars['decls'] = l_0_decls
    context.exported_vars.discard('decls')
    yield '// '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'header')))
    yield '\n//! Rust types of '
    yield str(t_1(environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'source')))
    yield ': one module per IDL module, XCDR1\n//! encode/decode through `cdr::serialize` / `cdr::deserialize` (docs/rust-backend.md).\n//! Features: `serde` (Serialize / Deserialize on every type), `dds` (RustDDS glue, `dds`).\n#![forbid(unsafe_code)]\n\npub mod cdr;\n'
    if (undefined(name='asset') if l_0_asset is missing else l_0_asset):
        pass
        yield 'pub mod asset;\n'
    yield '#[cfg(feature = "dds")]\npub mod dds;\n'
    if environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'serde_arrays'):
        pass
        yield '#[cfg(feature = "serde")]\npub mod serde_arrays;\n'
    yield '\n/// Every struct and union of the crate: what a DDS topic carries. With the `serde` feature\n/// also serde\'s traits, with `dds` also RustDDS\'s `Keyed` (its key: `dds::KeyBytes`).\n#[cfg(not(feature = "serde"))]\npub trait TopicType:\n    cdr::Cdr + ::core::fmt::Debug + ::core::clone::Clone + ::core::cmp::PartialEq + ::core::default::Default + \'static\n{\n}\n\n/// Every struct and union of the crate: what a DDS topic carries. With the `serde` feature\n/// also serde\'s traits, with `dds` also RustDDS\'s `Keyed` (its key: `dds::KeyBytes`).\n#[cfg(all(feature = "serde", not(feature = "dds")))]\npub trait TopicType:\n    cdr::Cdr + ::core::fmt::Debug + ::core::clone::Clone + ::core::cmp::PartialEq + ::core::default::Default + \'static\n    + ::serde::Serialize + ::serde::de::DeserializeOwned\n{\n}\n\n/// Every struct and union of the crate: what a DDS topic carries. With the `serde` feature\n/// also serde\'s traits, with `dds` also RustDDS\'s `Keyed` (its key: `dds::KeyBytes`).\n#[cfg(feature = "dds")]\npub trait TopicType:\n    cdr::Cdr + ::core::fmt::Debug + ::core::clone::Clone + ::core::cmp::PartialEq + ::core::default::Default + \'static\n    + ::serde::Serialize + ::serde::de::DeserializeOwned + ::rustdds::Keyed<K = dds::KeyBytes<Self>>\n{\n}\n\n/// Called by `visit_types` with every struct and union type of the crate.\npub trait TypeVisitor {\n    fn visit<T: TopicType>(&mut self);\n}\n\n/// Calls `v.visit::<T>()` for every struct and union (`T::TYPE_NAME` is its DDS name).\npub fn visit_types<V: TypeVisitor>('
    yield str(('v' if environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'types') else '_v'))
    yield ': &mut V) {\n'
    for l_1_t in environment.getattr((undefined(name='c') if l_0_c is missing else l_0_c), 'types'):
        _loop_vars = {}
        pass
        yield '    v.visit::<'
        yield str(l_1_t)
        yield '>();\n'
    l_1_t = missing
    yield '}\n'
    yield str(context.call((undefined(name='decls') if l_0_decls is missing else l_0_decls), (undefined(name='m') if l_0_m is missing else l_0_m)))
    yield '\n'

blocks = {}
debug_info = '1=21&2=28&3=30&9=32&14=36&51=40&52=42&53=46&56=50'
