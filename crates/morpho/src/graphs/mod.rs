//! Geometric graphs on point sets (Veltkamp 1992, ch. 2) and the γ-neighborhood graph (ch. 3).
//!
//! - [`brute`]: every graph straight from its definition (the oracles; Thm 3.1's brute force).
//! - [`gamma`]: the γ-neighbourhood as an interval of empty-ball centres, γ-values, Lemmas
//!   3.1–3.2.

pub mod brute;
pub mod gamma;

#[cfg(test)]
mod tests;
