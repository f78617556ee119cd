// A Fast DDS 2.9 TopicDataType for any generated struct (topics.hpp names one per type).
// Every package carries the same copy under the same guard. Its source is rapidgen's
// runtime/cpp/support/dds.hpp: edit it there.
#ifndef RAPIDGEN_DDS_SUPPORT_V1
#define RAPIDGEN_DDS_SUPPORT_V1

#include <cstdint>
#include <functional>
#include <vector>

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/InstanceHandle.h>
#include <fastdds/rtps/common/SerializedPayload.h>
#include <fastrtps/utils/md5.h>

#include "cdr.hpp"

namespace rapidgen {
namespace dds {

// Specialised per type in topics.hpp: name (the IDL scoped name), keyed, key_max (the
// largest key in bytes), initial_size (what Fast DDS preallocates), key(w, v).
template <class T>
struct Traits;

template <class T>
class TopicType : public eprosima::fastdds::dds::TopicDataType {
public:
    using type = T;

    TopicType() {
        setName(Traits<T>::name);
        m_typeSize = Traits<T>::initial_size;
        m_isGetKeyDefined = Traits<T>::keyed;
    }

    bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
        if (payload->max_size < 4) return false;
        try {
            cdr::Writer w(payload->data + 4, payload->max_size - 4);
            encode(w, *static_cast<const T*>(data));
            payload->data[0] = 0;
            payload->data[1] = cdr::host == cdr::Endianness::little ? 1 : 0;
            payload->data[2] = 0;
            payload->data[3] = 0;
            payload->encapsulation = cdr::host == cdr::Endianness::little ? CDR_LE : CDR_BE;
            payload->length = static_cast<std::uint32_t>(w.size() + 4);
            return true;
        } catch (const cdr::EncodeError&) {
            return false;
        }
    }

    bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
        try {
            cdr::deserialize(payload->data, payload->length, *static_cast<T*>(data));
            return true;
        } catch (const cdr::DecodeError&) {
            return false;
        }
    }

    std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
        return [data]() -> std::uint32_t {
            cdr::Counter w;
            encode(w, *static_cast<const T*>(data));
            return static_cast<std::uint32_t>(w.size() + 4);
        };
    }

    void* createData() override { return new T(); }
    void deleteData(void* data) override { delete static_cast<T*>(data); }

    // As fastddsgen's code: the key members in big-endian CDR; their MD5 when the key can
    // exceed 16 bytes (or force_md5), else the bytes themselves, zero-padded.
    bool getKey(void* data, eprosima::fastrtps::rtps::InstanceHandle_t* handle, bool force_md5 = false) override {
        if constexpr (!Traits<T>::keyed) {
            (void)data;
            (void)handle;
            (void)force_md5;
            return false;
        } else {
            const T& value = *static_cast<const T*>(data);
            cdr::Counter c;
            Traits<T>::key(c, value);
            // Fast DDS asks for the key of every sample written and received: a key that fits
            // (RAPID's header names: 72 bytes) is built on the stack, so a steady stream
            // allocates nothing here (docs/realtime.md).
            std::uint8_t small[256];
            std::vector<std::uint8_t> large;
            std::uint8_t* key = small;
            const std::size_t size = c.size();
            if (size > sizeof small) {
                large.resize(size);
                key = large.data();
            }
            if (cdr::host == cdr::Endianness::big) {
                cdr::Writer w(key, size);
                Traits<T>::key(w, value);
            } else {
                cdr::SwappedWriter w(key, size);
                Traits<T>::key(w, value);
            }
            if (force_md5 || Traits<T>::key_max > 16) {
                ::MD5 md5;  // Fast DDS 2.9 declares it at global scope
                md5.init();
                md5.update(key, static_cast<unsigned int>(size));
                md5.finalize();
                for (std::size_t i = 0; i < 16; ++i) handle->value[i] = md5.digest[i];
            } else {
                for (std::size_t i = 0; i < 16; ++i) handle->value[i] = i < size ? key[i] : 0;
            }
            return true;
        }
    }
};

}  // namespace dds
}  // namespace rapidgen

#endif  // RAPIDGEN_DDS_SUPPORT_V1
