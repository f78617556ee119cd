# mypy: ignore-errors
# Template templates/cpp/dds.hpp.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "3140127acfdd09c8930697dddae670cd48f6c0ba109eb7995aaf0a3acbfab5cc"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = 'dds.hpp.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_header = resolve('header')
    try:
        t_1 = environment.filters['cpp_comment']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No filter named 'cpp_comment' found.")
    pass
    yield '// '
    yield str(t_1((undefined(name='header') if l_0_header is missing else l_0_header)))
    yield '\n// A Fast DDS 2.9 TopicDataType for any generated struct (topics.hpp names one per type).\n// Every package carries the same copy under the same guard.\n#ifndef RAPIDGEN_DDS_SUPPORT_V1\n#define RAPIDGEN_DDS_SUPPORT_V1\n\n#include <cstdint>\n#include <functional>\n#include <vector>\n\n#include <fastdds/dds/topic/TopicDataType.hpp>\n#include <fastdds/rtps/common/InstanceHandle.h>\n#include <fastdds/rtps/common/SerializedPayload.h>\n#include <fastrtps/utils/md5.h>\n\n#include "cdr.hpp"\n\nnamespace rapidgen {\nnamespace dds {\n\n// Specialised per type in topics.hpp: name (the IDL scoped name), keyed, key_max (the\n// largest key in bytes), initial_size (what Fast DDS preallocates), key(w, v).\ntemplate <class T>\nstruct Traits;\n\ntemplate <class T>\nclass TopicType : public eprosima::fastdds::dds::TopicDataType {\npublic:\n    using type = T;\n\n    TopicType() {\n        setName(Traits<T>::name);\n        m_typeSize = Traits<T>::initial_size;\n        m_isGetKeyDefined = Traits<T>::keyed;\n    }\n\n    bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {\n        if (payload->max_size < 4) return false;\n        try {\n            cdr::Writer w(payload->data + 4, payload->max_size - 4);\n            encode(w, *static_cast<const T*>(data));\n            payload->data[0] = 0;\n            payload->data[1] = cdr::host == cdr::Endianness::little ? 1 : 0;\n            payload->data[2] = 0;\n            payload->data[3] = 0;\n            payload->encapsulation = cdr::host == cdr::Endianness::little ? CDR_LE : CDR_BE;\n            payload->length = static_cast<std::uint32_t>(w.size() + 4);\n            return true;\n        } catch (const cdr::EncodeError&) {\n            return false;\n        }\n    }\n\n    bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {\n        try {\n            cdr::deserialize(payload->data, payload->length, *static_cast<T*>(data));\n            return true;\n        } catch (const cdr::DecodeError&) {\n            return false;\n        }\n    }\n\n    std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {\n        return [data]() -> std::uint32_t {\n            cdr::Counter w;\n            encode(w, *static_cast<const T*>(data));\n            return static_cast<std::uint32_t>(w.size() + 4);\n        };\n    }\n\n    void* createData() override { return new T(); }\n    void deleteData(void* data) override { delete static_cast<T*>(data); }\n\n    // As fastddsgen\'s code: the key members in big-endian CDR; their MD5 when the key can\n    // exceed 16 bytes (or force_md5), else the bytes themselves, zero-padded.\n    bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5 = false) override {\n        if constexpr (!Traits<T>::keyed) {\n            (void)data;\n            (void)handle;\n            (void)force_md5;\n            return false;\n        } else {\n            const T& value = *static_cast<const T*>(data);\n            cdr::Counter c;\n            Traits<T>::key(c, value);\n            std::vector<std::uint8_t> key(c.size());\n            if (cdr::host == cdr::Endianness::big) {\n                cdr::Writer w(key.data(), key.size());\n                Traits<T>::key(w, value);\n            } else {\n                cdr::SwappedWriter w(key.data(), key.size());\n                Traits<T>::key(w, value);\n            }\n            if (force_md5 || Traits<T>::key_max > 16) {\n                ::MD5 md5;  // Fast DDS 2.9 declares it at global scope\n                md5.init();\n                md5.update(reinterpret_cast<const unsigned char*>(key.data()), static_cast<unsigned int>(key.size()));\n                md5.finalize();\n                for (std::size_t i = 0; i < 16; ++i) handle->value[i] = md5.digest[i];\n            } else {\n                for (std::size_t i = 0; i < 16; ++i) handle->value[i] = i < key.size() ? key[i] : 0;\n            }\n            return true;\n        }\n    }\n};\n\n}  // namespace dds\n}  // namespace rapidgen\n\n#endif  // RAPIDGEN_DDS_SUPPORT_V1\n'

blocks = {}
debug_info = '1=19'
