//! Handles: 64-bit numbers naming values kept here, so that a freed or made-up handle is an
//! error the caller can read instead of memory corrupted.
//!
//! A handle holds a slot's index plus one (its low 32 bits; 0 is never a handle) and the
//! slot's generation (its high 32 bits), which changes when the value is freed: a freed
//! handle stays invalid after its slot is reused.

/// Values behind handles.
#[derive(Debug)]
pub(crate) struct Registry<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
}

#[derive(Debug)]
struct Slot<T> {
    generation: u32,
    value: Option<T>,
}

impl<T> Registry<T> {
    pub(crate) const fn new() -> Self {
        Self {
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
        Some(u64::from(slot.generation) << 32 | u64::from(index + 1))
    }

    fn slot(&self, handle: u64) -> Option<(usize, u32)> {
        let index = (handle & 0xffff_ffff).checked_sub(1)? as usize;
        let generation = (handle >> 32) as u32;
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
        slot.generation = slot.generation.checked_add(1).unwrap_or(1);
        self.free.push(i as u32);
        Some(value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn freed_and_made_up_handles_find_nothing() {
        let mut r = Registry::new();
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
}
