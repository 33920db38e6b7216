//! Which bodies the user is pointing at and has picked: the pointer's cell, the body under it
//! (drawn highlighted, named with `--hover`) and the selected body (the last one clicked or
//! spawned, which WASD nudges, `<` `>` grow and the inspector shows). One owner, because a click,
//! a spawn, a reset and a rewind all change them together and must agree.

use crate::physics::BodyId;

/// The pointer and the bodies it points at and picked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Selection {
    /// Last known pointer cell (absolute terminal coordinates).
    pointer: Option<(u16, u16)>,
    /// Body under the pointer.
    highlighted: Option<BodyId>,
    /// The last body clicked or spawned.
    selected: Option<BodyId>,
}

impl Selection {
    pub fn pointer(&self) -> Option<(u16, u16)> {
        self.pointer
    }

    pub fn highlighted(&self) -> Option<BodyId> {
        self.highlighted
    }

    pub fn selected(&self) -> Option<BodyId> {
        self.selected
    }

    /// The pointer moved to `cell` (any mouse event says where it is).
    pub fn point_at(&mut self, cell: (u16, u16)) {
        self.pointer = Some(cell);
    }

    /// The body now under the pointer; true if that changed what is drawn highlighted.
    pub fn hover(&mut self, under: Option<BodyId>) -> bool {
        let changed = under != self.highlighted;
        self.highlighted = under;
        changed
    }

    /// A click on `id`: it is selected, and highlighted as the body under the pointer.
    pub fn click(&mut self, id: BodyId) {
        self.selected = Some(id);
        self.highlighted = Some(id);
    }

    /// A new body: selected, so WASD and `<` `>` act on what was just made.
    pub fn select(&mut self, id: BodyId) {
        self.selected = Some(id);
    }

    /// A reset: no body is picked or highlighted (the pointer stays where it is).
    pub fn clear_bodies(&mut self) {
        self.selected = None;
        self.highlighted = None;
    }

    /// A rewind left `len` bodies: forgets those of the cut-off future.
    pub fn forget_from(&mut self, len: usize) {
        self.selected = self.selected.filter(|id| id.index() < len);
        self.highlighted = self.highlighted.filter(|id| id.index() < len);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rewind_forgets_only_the_bodies_it_removed() {
        let mut selection = Selection::default();
        selection.click(BodyId(3));
        selection.forget_from(4);
        assert_eq!(selection.selected(), Some(BodyId(3)));
        selection.forget_from(3);
        assert_eq!(selection.selected(), None);
        assert_eq!(selection.highlighted(), None);
    }

    #[test]
    fn hovering_says_whether_the_highlight_changed() {
        let mut selection = Selection::default();
        assert!(selection.hover(Some(BodyId(1))));
        assert!(!selection.hover(Some(BodyId(1))));
        assert!(selection.hover(None));
    }
}
