//! Geometric graphs on point sets (Veltkamp 1992, ch. 2) and the γ-neighborhood graph (ch. 3).
//!
//! - [`brute`]: every graph straight from its definition (the oracles; Thm 3.1's brute force).
//! - [`gamma`]: the γ-neighbourhood as an interval of empty-ball centres, γ-values, Lemmas
//!   3.1–3.2.

pub mod beyond3;
pub mod brute;
pub mod build;
pub mod fast;
pub mod gamma;
pub mod lune;

pub use build::{graph_2d, graph_3d, Graph, Kind};

#[cfg(test)]
mod tests;
