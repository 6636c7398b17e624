//! Gradients of volumes: Zucker–Hummel and central differences (Hamann 1991 §3.4). TODO(helper): issue 6.
