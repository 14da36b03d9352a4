"""The chapter's closed-form results, one function per equation (numerical twins in analysis/)."""
