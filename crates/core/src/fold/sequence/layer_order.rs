//! Which of the sequences that land alike is the one made: two perpendicular half folds
//! done in either order land alike on the table, but for a rigid motion, which no disk
//! sees; what tells them apart is the order of their layers.

use crate::border::Point;
use crate::metrics::aligned_rmse_xy;

use super::beam::Judged;
use crate::fold::params::Params;
#[cfg(doc)]
use crate::fold::params::{LayerOrderParams, SelectionParams};
use crate::fold::probe::Probe;

/// Take out of `judged` (best first) the sequence of least mismatch, but that one which
/// explains the end disk about as well ([`SelectionParams::about_as_well_share`]) and lands
/// like it (within [`LayerOrderParams::congruent`]), its layers stacked in another order,
/// whose heights fit the measured disk better, on each one's outline, on `probe`, and which
/// moves the cloth from `before` not markedly further ([`LayerOrderParams::further_share`]).
pub(super) fn layer_order(
    before: &[Point],
    probe: &Probe,
    judged: &mut Vec<Judged>,
    params: &Params,
) -> Option<Judged> {
    let (order, about_as_well) = (&params.layer_order, params.selection.about_as_well_share);
    let with = |xy: &[Point], z: &[Point]| -> Vec<Point> {
        xy.iter().zip(z).map(|(p, q)| Point::new(p.x, p.y, q.z)).collect()
    };
    // How far each moves the cloth across the table.
    let moved: Vec<f64> = judged
        .iter()
        .map(|j| j.state.iter().zip(before).map(|(p, q)| (p.xy() - q.xy()).norm()).sum::<f64>())
        .collect();
    let mut best = 0;
    for k in 1..judged.len() {
        let (a, b) = (&judged[best].state, &judged[k].state);
        if judged[k].cost > (1.0 + about_as_well) * judged[0].cost
            || aligned_rmse_xy(a, b) > order.congruent
            || moved[k] > (1.0 + order.further_share) * moved[best]
        {
            continue;
        }
        // Positive when the other's heights fit better, on either outline.
        let evidence = (probe.cost_of_state(a) - probe.cost_of_state(&with(a, b)))
            + (probe.cost_of_state(&with(b, a)) - probe.cost_of_state(b));
        if evidence > 0.0 {
            best = k;
        }
    }
    (!judged.is_empty()).then(|| judged.remove(best))
}
