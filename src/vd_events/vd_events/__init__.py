"""vd events: event runner, recorder, post-processing and the vd command-line tool."""
