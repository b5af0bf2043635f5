//! The scene in serde's data model (the web page's worker sends it, `crates/web/src/wire`): its
//! GPU buffers as their bytes, one copy each way (a million face corners cross in a few
//! milliseconds, not element by element), read back into aligned buffers and checked by
//! [`Scene::from_parts`].

use serde::de::{Error as _, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use bytemuck::Pod;

use crate::scene::{Scene, SceneParts};

/// Writes a buffer as its bytes (for `#[serde(with = "crate::scene_bytes")]`).
pub(crate) fn serialize<T: Pod, S: Serializer>(items: &[T], s: S) -> Result<S::Ok, S::Error> {
    s.serialize_bytes(bytemuck::cast_slice(items))
}

/// Reads a buffer from its bytes (a whole number of items; copied into aligned storage).
pub(crate) fn deserialize<'de, T: Pod, D: Deserializer<'de>>(d: D) -> Result<Vec<T>, D::Error> {
    d.deserialize_bytes(PodVisitor(std::marker::PhantomData))
}

struct PodVisitor<T>(std::marker::PhantomData<T>);

impl<T: Pod> Visitor<'_> for PodVisitor<T> {
    type Value = Vec<T>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "a buffer of {}-byte items", size_of::<T>())
    }

    fn visit_bytes<E: serde::de::Error>(self, bytes: &[u8]) -> Result<Vec<T>, E> {
        if !bytes.len().is_multiple_of(size_of::<T>()) {
            return Err(E::custom(format!(
                "a buffer of {} bytes is not a whole number of {}-byte items",
                bytes.len(),
                size_of::<T>()
            )));
        }
        Ok(bytemuck::pod_collect_to_vec(bytes))
    }

    fn visit_byte_buf<E: serde::de::Error>(self, bytes: Vec<u8>) -> Result<Vec<T>, E> {
        self.visit_bytes(&bytes)
    }
}

impl Serialize for Scene {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.parts().serialize(s)
    }
}

impl<'de> Deserialize<'de> for Scene {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Scene::from_parts(SceneParts::deserialize(d)?)
            .ok_or_else(|| D::Error::custom("a triangle index past the face vertices"))
    }
}
