"""vd data side: vehicle data files, master files, feedback, data-server node."""
