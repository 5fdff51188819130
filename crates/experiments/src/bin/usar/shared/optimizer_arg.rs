//! `--optimizer`'s values ([`OptimizerArg`]), as `usar calibrate` and `usar multiverse` take
//! them.

/// `--optimizer`'s values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum OptimizerArg {
    /// Nelder-Mead (argmin).
    NelderMead,
    /// CMA-ES (fcmaes-core).
    CmaEs,
}

impl From<OptimizerArg> for usar_study::calibrate::Optimizer {
    fn from(a: OptimizerArg) -> Self {
        match a {
            OptimizerArg::NelderMead => Self::NelderMead,
            OptimizerArg::CmaEs => Self::CmaEs,
        }
    }
}
