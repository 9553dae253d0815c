//! Handles: 64-bit numbers naming values kept here, so that a freed, made-up or mistaken
//! handle is an error the caller can read instead of memory corrupted.
//!
//! A handle holds a slot's index plus one (its low 32 bits; 0 is never a handle), the slot's
//! generation (bits 32-55), which changes when the value is freed, so that a freed handle stays
//! invalid after its slot is reused, and its registry's kind (bits 56-63), so that a law's
//! handle given where a contact's is expected (or the reverse) is found out.

/// What a registry holds: the tag its handles carry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Laws (`BwcLaw`).
    Law = 1,
    /// Contact elements (`BwcContact`).
    Contact = 2,
}

impl Kind {
    /// The kind a handle's tag names, if any.
    pub(crate) fn of(handle: u64) -> Option<Self> {
        match handle >> 56 {
            1 => Some(Self::Law),
            2 => Some(Self::Contact),
            _ => None,
        }
    }

    /// The kind's name in messages.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Self::Law => "law",
            Self::Contact => "contact",
        }
    }
}

use crate::status::{BwcStatus, Failure};

/// Generations run through 24 bits.
const GENERATIONS: u32 = 0x00ff_ffff;

/// Values behind handles.
#[derive(Debug)]
pub(crate) struct Registry<T> {
    kind: Kind,
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
}

#[derive(Debug)]
struct Slot<T> {
    generation: u32,
    value: Option<T>,
}

impl<T> Registry<T> {
    pub(crate) const fn new(kind: Kind) -> Self {
        Self {
            kind,
            slots: Vec::new(),
            free: Vec::new(),
        }
    }

    /// Keeps `value`; its handle, or `None` when all 2^32 - 1 slots are taken.
    pub(crate) fn insert(&mut self, value: T) -> Option<u64> {
        let index = match self.free.pop() {
            Some(i) => i,
            None => {
                let i = u32::try_from(self.slots.len())
                    .ok()
                    .filter(|&i| i < u32::MAX)?;
                self.slots.push(Slot {
                    generation: 1,
                    value: None,
                });
                i
            }
        };
        let slot = &mut self.slots[index as usize];
        slot.value = Some(value);
        Some((self.kind as u64) << 56 | u64::from(slot.generation) << 32 | u64::from(index + 1))
    }

    fn slot(&self, handle: u64) -> Option<(usize, u32)> {
        if Kind::of(handle) != Some(self.kind) {
            return None;
        }
        let index = (handle & 0xffff_ffff).checked_sub(1)? as usize;
        let generation = (handle >> 32) as u32 & GENERATIONS;
        (self.slots.get(index)?.generation == generation).then_some((index, generation))
    }

    /// The value of a live handle.
    pub(crate) fn get(&self, handle: u64) -> Option<&T> {
        let (i, _) = self.slot(handle)?;
        self.slots[i].value.as_ref()
    }

    /// Frees a live handle's value; later calls with it find nothing.
    pub(crate) fn remove(&mut self, handle: u64) -> Option<T> {
        let (i, _) = self.slot(handle)?;
        let slot = &mut self.slots[i];
        let value = slot.value.take()?;
        slot.generation = if slot.generation >= GENERATIONS {
            1
        } else {
            slot.generation + 1
        };
        self.free.push(i as u32);
        Some(value)
    }
}

/// The failure for argument `name`, which expects a handle of kind `expected`, given `handle`:
/// one of another kind, or one not live.
pub(crate) fn dead(name: &str, handle: u64, expected: Kind) -> Failure {
    let message = match Kind::of(handle) {
        Some(kind) if kind != expected => format!(
            "argument `{name}` = {handle:#x} is a {} handle, not a {} handle",
            kind.name(),
            expected.name()
        ),
        _ => format!(
            "argument `{name}` = {handle:#x} is not a live handle: it was freed, or did not \
             come from a bwc_*_new function"
        ),
    };
    Failure::new(BwcStatus::InvalidHandle, message)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn freed_and_made_up_handles_find_nothing() {
        let mut r = Registry::new(Kind::Law);
        let a = r.insert("a").unwrap();
        assert_eq!(r.get(a), Some(&"a"));
        assert_eq!(r.get(0), None);
        assert_eq!(r.get(a + 1), None);
        assert_eq!(r.remove(a), Some("a"));
        assert_eq!(r.get(a), None);
        assert_eq!(r.remove(a), None);
        // The slot is reused under a new generation: the old handle stays dead.
        let b = r.insert("b").unwrap();
        assert_ne!(a, b);
        assert_eq!(r.get(a), None);
        assert_eq!(r.get(b), Some(&"b"));
    }

    #[test]
    fn a_handle_of_another_kind_finds_nothing() {
        let mut laws = Registry::new(Kind::Law);
        let mut contacts = Registry::new(Kind::Contact);
        let law = laws.insert("law").unwrap();
        let contact = contacts.insert("contact").unwrap();
        // The same slot and generation in both: only the kind tells them apart.
        assert_eq!(law & 0x00ff_ffff_ffff_ffff, contact & 0x00ff_ffff_ffff_ffff);
        assert_eq!(contacts.get(law), None);
        assert_eq!(laws.get(contact), None);
        assert_eq!(Kind::of(law), Some(Kind::Law));
        assert_eq!(Kind::of(contact), Some(Kind::Contact));
        assert_eq!(Kind::of(1), None);
    }
}
