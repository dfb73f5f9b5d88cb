"""Who may do what at the station: roles, the development PKI, bearer tokens and the audit log.

Nothing here imports grpc; the runtime (services.runtime.auth, services.runtime.tls) applies it
to calls and channels.
"""
