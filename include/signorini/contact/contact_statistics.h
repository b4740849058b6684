#ifndef signorini_contact_contact_statistics_h
#define signorini_contact_contact_statistics_h

namespace Signorini
{
  namespace Contact
  {
    /** Counts and norms of one contact residual evaluation. */
    struct ContactStatistics
    {
      unsigned int n_points   = 0; // all contact points
      unsigned int n_unpaired = 0; // no master face found
      unsigned int n_contact  = 0; // chi_c = 1
      unsigned int n_stick    = 0;
      unsigned int n_slip     = 0;
      unsigned int n_changed  = 0; // status differs from the last evaluation
      unsigned int n_reversed = 0; // slip direction turned by > 90 degrees
      // Anti-cycling (theory.md F8), counted at new iterates only:
      unsigned int n_cycling      = 0; // points back to their status of k-2
      unsigned int n_frozen       = 0; // points whose status is frozen now
      unsigned int n_newly_frozen = 0; // frozen at this evaluation
      unsigned int n_violated     = 0; // frozen, but the plain law disagrees
      // Frozen by the geometric loop (kept to the end of the load step),
      // and among them those the plain law disagrees with.
      unsigned int n_geometric_frozen   = 0;
      unsigned int n_geometric_violated = 0;
    };
  } // namespace Contact
} // namespace Signorini

#endif
