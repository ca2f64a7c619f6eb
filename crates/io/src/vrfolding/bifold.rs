//! Cutting a VR-Folding recording into fold actions, by BiFold's rule.
//!
//! Barbany et al., "BiFold" (ICRA 2025), as used by Kamat, Borràs, Torras ("CloSE", §V,
//! Table I) to turn VR-Folding's continuous recordings into single folds: a frame *grips*
//! when either hand holds at least one vertex (a hand that holds nothing stores `[-1]`). A
//! fold action starts at the first frame that grips and ends at the last frame before both
//! hands have let go; one hand letting go while the other still holds does not end it. An
//! action still open when the video ends never ended, so it is not an action (BiFold keeps
//! only actions whose release it saw).
//!
//! ```
//! use close_io::vrfolding::bifold::actions;
//! // idle, grip, grip, release, grip, release
//! let grips = [false, true, true, false, true, false];
//! let a = actions(&grips);
//! assert_eq!((a.actions[0].start, a.actions[0].end), (1, 2));
//! assert_eq!((a.actions[1].start, a.actions[1].end), (4, 4));
//! assert!(!a.unfinished);
//! ```

/// One fold action: frames `start ..= end` of a video (positions in `sample_id` order).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Action {
    pub start: usize,
    pub end: usize,
}

/// The actions of one video.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Actions {
    pub actions: Vec<Action>,
    /// True when a hand still gripped in the last frame (that action is not counted).
    pub unfinished: bool,
}

/// The actions of a video from, per frame, whether either hand grips.
pub fn actions(grips: &[bool]) -> Actions {
    let mut out = Actions::default();
    let mut open: Option<usize> = None;
    for (k, &gripping) in grips.iter().enumerate() {
        match (open, gripping) {
            (None, true) => open = Some(k),
            (Some(start), false) => {
                out.actions.push(Action { start, end: k - 1 });
                open = None;
            }
            _ => {}
        }
    }
    out.unfinished = open.is_some();
    out
}

/// Whether a hand grips, from its stored vertex ids (`[-1]`, or empty, when it holds nothing).
pub fn holds(ids: &[i64]) -> bool {
    ids.first().is_some_and(|&v| v >= 0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_hand_letting_go_does_not_end_the_action() {
        // Left: grips frames 1..=4; right: 1..=2. The action lasts while either holds.
        let left = [false, true, true, true, true, false, false];
        let right = [false, true, true, false, false, false, true];
        let either: Vec<bool> = left.iter().zip(&right).map(|(l, r)| *l || *r).collect();
        let a = actions(&either);
        assert_eq!(a.actions, vec![Action { start: 1, end: 4 }]);
        assert!(a.unfinished, "the right hand grips again in the last frame");
    }

    #[test]
    fn no_grip_means_no_action() {
        assert_eq!(actions(&[false; 5]), Actions::default());
        assert_eq!(actions(&[]), Actions::default());
    }

    #[test]
    fn a_grip_from_the_first_frame_starts_there() {
        let a = actions(&[true, true, false, true, false]);
        assert_eq!(a.actions, vec![Action { start: 0, end: 1 }, Action { start: 3, end: 3 }]);
    }

    #[test]
    fn holding_is_a_non_negative_first_id() {
        assert!(holds(&[12, 40]));
        assert!(holds(&[0]));
        assert!(!holds(&[-1]));
        assert!(!holds(&[]));
    }
}
