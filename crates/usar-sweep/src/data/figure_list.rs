//! The figures of a sweep as output names: each figure's file name, title, y-axis label and
//! quantity ([`FIGURES`]). `usar_report::figures` draws them; the reports link them and a new
//! sweep removes the earlier sweep's copies by these names.

use crate::metrics::Quantity;

/// One figure: file name, title, y-axis label and the quantity shown for each task and the
/// total.
#[derive(Debug, Clone, Copy)]
pub struct FigureSpec {
    /// File name in the output folder.
    pub file: &'static str,
    /// Title drawn above the chart.
    pub title: &'static str,
    /// Y-axis label.
    pub y_label: &'static str,
    /// The quantity drawn, per task and in total.
    pub quantity: Quantity,
}

/// The three figures of a sweep: (a) rescuees, (b) energy cost per rescuee, (c) HP cost per
/// rescuee.
pub const FIGURES: [FigureSpec; 3] = [
    FigureSpec {
        file: "fig3a_rescuees.svg",
        title: "(a) Rescuees per trial",
        y_label: "rescuees",
        quantity: Quantity::Rescued,
    },
    FigureSpec {
        file: "fig3b_energy_per_rescuee.svg",
        title: "(b) Energy cost per rescuee",
        y_label: "energy per rescuee (% points)",
        quantity: Quantity::EnergyPerRescuee,
    },
    FigureSpec {
        file: "fig3c_hp_per_rescuee.svg",
        title: "(c) HP cost per rescuee",
        y_label: "HP per rescuee (% points)",
        quantity: Quantity::HpPerRescuee,
    },
];
