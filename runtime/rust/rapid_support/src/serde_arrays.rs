//! serde for the members holding an array longer than 32 elements, the longest serde's own
//! impls take (feature `serde`): `#[serde(with = "crate::serde_arrays::Arr::<...>")]`,
//! composed like the member's type (`Arr` an array level, `Seq` a sequence, `Plain` the
//! element's own impls). An array is written as a tuple of its length, as serde writes
//! shorter ones, so every length looks alike (a JSON list); reading one refuses any other
//! length. A crate gets this module only when one of its members needs it.

use ::core::fmt;
use ::core::marker::PhantomData;
use ::serde::de::{DeserializeOwned, DeserializeSeed, Deserializer, Error, SeqAccess, Visitor};
use ::serde::ser::{Serialize, SerializeSeq, SerializeTuple, Serializer};

/// How a value of `T` is written and read.
pub trait Way<T> {
    fn ser<S: Serializer>(v: &T, s: S) -> ::core::result::Result<S::Ok, S::Error>;
    fn de<'de, D: Deserializer<'de>>(d: D) -> ::core::result::Result<T, D::Error>;
}

/// `T`'s own `Serialize` and `Deserialize`.
pub enum Plain {}

/// An array `[T; N]` of any length, each element written and read by `W`.
pub struct Arr<W>(PhantomData<W>);

/// A `Vec<T>`, each element written and read by `W`.
pub struct Seq<W>(PhantomData<W>);

impl<T: Serialize + DeserializeOwned> Way<T> for Plain {
    fn ser<S: Serializer>(v: &T, s: S) -> ::core::result::Result<S::Ok, S::Error> {
        v.serialize(s)
    }
    fn de<'de, D: Deserializer<'de>>(d: D) -> ::core::result::Result<T, D::Error> {
        T::deserialize(d)
    }
}

/// A value written by `W` (an element of an `Arr` or `Seq`).
struct By<'a, T, W>(&'a T, PhantomData<W>);

impl<T, W: Way<T>> Serialize for By<'_, T, W> {
    fn serialize<S: Serializer>(&self, s: S) -> ::core::result::Result<S::Ok, S::Error> {
        W::ser(self.0, s)
    }
}

/// A value read by `W`.
struct Seed<T, W>(PhantomData<(T, W)>);

impl<'de, T, W: Way<T>> DeserializeSeed<'de> for Seed<T, W> {
    type Value = T;
    fn deserialize<D: Deserializer<'de>>(self, d: D) -> ::core::result::Result<T, D::Error> {
        W::de(d)
    }
}

/// Collects a sequence's elements: exactly `len` of them for an array, else at most what
/// the input holds (allocating no more up front than 4096 elements).
struct Collect<T, W> {
    len: Option<usize>,
    _way: PhantomData<(T, W)>,
}

impl<'de, T, W: Way<T>> Visitor<'de> for Collect<T, W> {
    type Value = ::std::vec::Vec<T>;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.len {
            Some(n) => write!(f, "an array of {n} elements"),
            None => f.write_str("a sequence"),
        }
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> ::core::result::Result<Self::Value, A::Error> {
        let room = self.len.or_else(|| seq.size_hint()).unwrap_or(0).min(4096);
        let mut out = ::std::vec::Vec::with_capacity(room);
        while self.len.map_or(true, |n| out.len() < n) {
            match seq.next_element_seed(Seed::<T, W>(PhantomData))? {
                Some(e) => out.push(e),
                None if self.len.is_some() => return Err(A::Error::invalid_length(out.len(), &self)),
                None => break,
            }
        }
        Ok(out)
    }
}

impl<T, W: Way<T>, const N: usize> Way<[T; N]> for Arr<W> {
    fn ser<S: Serializer>(v: &[T; N], s: S) -> ::core::result::Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(N)?;
        for e in v {
            t.serialize_element(&By::<T, W>(e, PhantomData))?;
        }
        t.end()
    }
    fn de<'de, D: Deserializer<'de>>(d: D) -> ::core::result::Result<[T; N], D::Error> {
        let v = d.deserialize_tuple(N, Collect::<T, W> { len: Some(N), _way: PhantomData })?;
        let got = v.len();
        <[T; N]>::try_from(v).map_err(|_| D::Error::invalid_length(got, &"an array of its declared length"))
    }
}

impl<T, W: Way<T>> Way<::std::vec::Vec<T>> for Seq<W> {
    fn ser<S: Serializer>(v: &::std::vec::Vec<T>, s: S) -> ::core::result::Result<S::Ok, S::Error> {
        Self::serialize(v, s)
    }
    fn de<'de, D: Deserializer<'de>>(d: D) -> ::core::result::Result<::std::vec::Vec<T>, D::Error> {
        d.deserialize_seq(Collect::<T, W> { len: None, _way: PhantomData })
    }
}

// `#[serde(with = ...)]` calls `serialize` and `deserialize` on the path it names.
impl<W> Arr<W> {
    pub fn serialize<T, S: Serializer, const N: usize>(v: &[T; N], s: S) -> ::core::result::Result<S::Ok, S::Error>
    where
        Self: Way<[T; N]>,
    {
        <Self as Way<[T; N]>>::ser(v, s)
    }
    pub fn deserialize<'de, T, D: Deserializer<'de>, const N: usize>(d: D) -> ::core::result::Result<[T; N], D::Error>
    where
        Self: Way<[T; N]>,
    {
        <Self as Way<[T; N]>>::de(d)
    }
}

impl<W> Seq<W> {
    pub fn serialize<T, S: Serializer>(v: &[T], s: S) -> ::core::result::Result<S::Ok, S::Error>
    where
        W: Way<T>,
    {
        let mut q = s.serialize_seq(Some(v.len()))?;
        for e in v {
            q.serialize_element(&By::<T, W>(e, PhantomData))?;
        }
        q.end()
    }
    pub fn deserialize<'de, T, D: Deserializer<'de>>(d: D) -> ::core::result::Result<::std::vec::Vec<T>, D::Error>
    where
        Self: Way<::std::vec::Vec<T>>,
    {
        <Self as Way<::std::vec::Vec<T>>>::de(d)
    }
}
