# mypy: ignore-errors
# Template templates/python/_support.py.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "3e8b1b89b36cf90c6b99bb5aca85386e8b6872a62be50a92b81832858f75acb8"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_support.py.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    try:
        t_1 = environment.filters['comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'comment' found.")
    pass
    yield '# '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n"""Helpers the generated modules use (kept here so the modules stay declarative)."""\n\nimport struct\nimport typing\n\nimport cyclonedds.idl.types as types\n\n\ndef sequence(subtype, bound):\n    """The annotation `types.sequence[subtype, bound]`, for any bound.\n\n    cyclonedds 11.0.1\'s subscript form refuses bounds above 65535 (it returns an error\n    object instead of the annotation); this builds the same annotation directly.\n    """\n    return typing.Annotated[typing.Sequence[subtype], types.sequence(subtype, bound)]\n\n\nclass DeserializeError(ValueError):\n    """Bytes that are not a valid encoding of the type: truncated or overlong data, a length\n    or discriminator out of range, text that is not UTF-8, an unknown enumerator."""\n\n\n# What cyclonedds 11\'s decoder raises on bad bytes (struct.error: data too short;\n# UnicodeDecodeError and ValueError: bad text or enumerator; the others: bad lengths/cases).\n_BAD_BYTES = (struct.error, ValueError, IndexError, KeyError, OverflowError)\n\n\ndef checked(cls):\n    """Class decorator: cls.deserialize and cls.deserialize_key raise DeserializeError, and\n    only that, for bad bytes; what they return for good bytes is unchanged."""\n    for name in ("deserialize", "deserialize_key"):\n        plain = getattr(cls, name).__func__\n\n        def guarded(klass, data, *args, _plain=plain, _name=name, **kwargs):\n            try:\n                return _plain(klass, data, *args, **kwargs)\n            except _BAD_BYTES as exc:\n                raise DeserializeError(f"{klass.__name__}.{_name}: not a valid encoding "\n                                       f"({type(exc).__name__}: {exc})") from exc\n\n        guarded.__name__ = guarded.__qualname__ = name\n        guarded.__doc__ = f"cyclonedds\' {name}; bad bytes raise DeserializeError."\n        setattr(cls, name, classmethod(guarded))\n    return cls\n'

blocks = {}
debug_info = '1=19'
