//! Model fitting: a robust least-squares solver inside argmin, fit reports
//! with honest uncertainties, and the Coulomb and ice-friction fits.
