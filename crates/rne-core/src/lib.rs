//! Relative Needs Entropy (RNE) trust model and RNE-based grouping.
//!
//! Pure math, no physics. Reference: Q. Yang and R. Parasuraman, "How Can Robots Trust Each
//! Other For Better Cooperation? A Relative Needs Entropy Based Robot-Robot Trust Assessment
//! Model", IEEE SMC 2021.
