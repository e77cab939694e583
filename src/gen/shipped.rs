//! The models shipped in `models/<room>/` (and the low-noise experts in `models/<room>-expert/`),
//! embedded into the library at build time, so that `generate` and `demo` need no files beside
//! the binary.

use super::checkpoint::parse_meta;
use super::{Checkpoint, GenError, Generator};
use crate::scene::RoomType;
use std::path::PathBuf;

include!(concat!(env!("OUT_DIR"), "/shipped_models.rs"));

/// The shipped model for `room`.
pub fn shipped_model(room: RoomType) -> Result<Checkpoint, GenError> {
    let origin = origin(room, "");
    let checkpoint = embedded(SHIPPED, room, "").ok_or_else(|| {
        GenError::checkpoint(&origin, format!("no {room} model was shipped with this build; pass --model DIR"))
    })??;
    if !checkpoint.meta.model.serves(room) {
        let message = format!("shipped config is for {}", checkpoint.meta.model.room_names());
        return Err(GenError::checkpoint(&origin, message));
    }
    Ok(checkpoint)
}

/// The shipped low-noise expert for `room` ([`super::ModelConfig::expert_below`]), if one was
/// shipped (`models/<room>-expert/`).
pub fn shipped_expert(room: RoomType) -> Result<Option<Checkpoint>, GenError> {
    embedded(SHIPPED_EXPERTS, room, "-expert").transpose()
}

/// The generator of the shipped model for `room`, with its shipped expert if it has one.
pub fn shipped_generator(room: RoomType) -> Result<Generator, GenError> {
    let generator = Generator::new(shipped_model(room)?);
    match shipped_expert(room)? {
        Some(expert) => generator.with_expert(expert, &origin(room, "-expert")),
        None => Ok(generator),
    }
}

/// `room`'s checkpoint in one of the embedded tables, loaded (`None` where the table has none).
fn embedded(table: &[(&str, &str, &[u8])], room: RoomType, suffix: &str) -> Option<Result<Checkpoint, GenError>> {
    let (_, config, weights) = table.iter().find(|(r, _, _)| *r == room.name())?;
    let origin = origin(room, suffix);
    Some(
        parse_meta(config, &origin.join("config.json"))
            .and_then(|meta| Checkpoint::from_parts(meta, weights, &origin.join("model.safetensors"))),
    )
}

/// The folder `room`'s embedded model (`suffix` "") or expert (`"-expert"`) came from, as its
/// errors name it.
fn origin(room: RoomType, suffix: &str) -> PathBuf {
    PathBuf::from(format!("models/{}{suffix}", room.name()))
}

/// Room types with a shipped model.
pub fn shipped_rooms() -> Vec<RoomType> {
    RoomType::ALL.into_iter().filter(|r| SHIPPED.iter().any(|(name, _, _)| *name == r.name())).collect()
}

/// The shipped model's weights by name (tests that need trained values).
#[cfg(test)]
pub(crate) fn shipped_weights(room: RoomType) -> std::collections::BTreeMap<String, candle_core::Tensor> {
    let (_, _, weights) = SHIPPED.iter().find(|(r, _, _)| *r == room.name()).expect("a shipped model");
    super::checkpoint::read_tensors(weights, &PathBuf::from("model.safetensors"))
        .expect("shipped weights")
        .into_iter()
        .collect()
}
