#!/usr/bin/env node
// A Node.js client built from the .proto files alone, loaded at run time: it checks health and
// reads the robot's status and state. It shows that any language with gRPC can drive the robot.
//
//   node clients/node/client.js [host:port]      (default 127.0.0.1:50051, the DecisionServer)
//   TELEROBOT_TLS_DIR=var/pki [TELEROBOT_IDENTITY=observer] node clients/node/client.js [host:port]
//   node clients/node/client.js [host:port] --tls-dir var/pki [--identity observer]
//   TELEROBOT_TLS_DIR=var/pki TELEROBOT_TOKEN=trb_... node clients/node/client.js [host:port]
//
// Credentials, as the Python clients take them (wire/tls.py):
// - TELEROBOT_TLS_DIR (or --tls-dir): mutual TLS, trusting <dir>/ca.pem and presenting the
//   client certificate <dir>/<identity>.pem with <dir>/<identity>.key (`make certs` writes
//   var/pki). Unset: plaintext, which the station takes only without TLS, on loopback.
// - TELEROBOT_IDENTITY (or --identity): which certificate to present (default operator;
//   observer is enough for what this client reads).
// - TELEROBOT_TOKEN: with TELEROBOT_TLS_DIR, send `authorization: Bearer <token>` over TLS
//   instead of a client certificate (the DecisionServer's token port takes it). Without a TLS
//   directory it is ignored: a token is never sent in plaintext.
//
// It prints one JSON object and exits 0 when the server answered every call (an error status
// is an answer, and is reported with its code), 1 when the server could not be reached or the
// TLS handshake failed (then the object is {address, error}), 2 on a bad command line.
'use strict';

const fs = require('fs');
const path = require('path');
const grpc = require('@grpc/grpc-js');
const protoLoader = require('@grpc/proto-loader');

const PROTO_ROOT = path.resolve(__dirname, '..', '..', 'protos');
const HEALTH_PROTO = require.resolve('grpc-health-check/proto/health/v1/health.proto');
const LOADER_OPTIONS = { keepCase: true, longs: String, enums: String, defaults: true, oneofs: true };
const DEADLINE_MS = 3000;
const DEFAULT_ADDRESS = '127.0.0.1:50051';
const DEFAULT_IDENTITY = 'operator';
const USAGE = 'usage: node clients/node/client.js [host:port] [--tls-dir DIR] [--identity NAME]';

// The server certificates name 127.0.0.1 and ::1, so an address by IP verifies; Node warns
// (DEP0123) that grpc-js also sends the IP as the TLS server name. That warning is noise here.
const emitWarning = process.emitWarning;
process.emitWarning = function (warning, ...rest) {
  const code = typeof rest[0] === 'object' && rest[0] !== null ? rest[0].code : rest[1];
  if (code === 'DEP0123') return;
  emitWarning.call(process, warning, ...rest);
};

class UsageError extends Error {}

// The command line: [host:port] [--tls-dir DIR] [--identity NAME] (also --flag=value).
function parseArgs(argv) {
  const args = { address: null, tlsDir: null, identity: null };
  const flags = { '--tls-dir': 'tlsDir', '--identity': 'identity' };
  for (let i = 0; i < argv.length; i += 1) {
    const arg = argv[i];
    const [flag, inline] = arg.startsWith('--') && arg.includes('=')
      ? [arg.slice(0, arg.indexOf('=')), arg.slice(arg.indexOf('=') + 1)] : [arg, undefined];
    if (flag === '-h' || flag === '--help') {
      console.log(USAGE);
      process.exit(0);
    } else if (flag in flags) {
      const value = inline !== undefined ? inline : argv[++i];
      if (!value) throw new UsageError(`${flag} needs a value`);
      args[flags[flag]] = value;
    } else if (arg.startsWith('-')) {
      throw new UsageError(`unknown option ${arg}`);
    } else if (args.address === null) {
      args.address = arg;
    } else {
      throw new UsageError(`unexpected argument ${arg}`);
    }
  }
  return args;
}

// How the client authenticates: {credentials, description}; throws a plain Error with a hint
// when a file of the TLS directory cannot be read.
function channelSecurity(args) {
  const tlsDir = args.tlsDir || process.env.TELEROBOT_TLS_DIR || null;
  const token = process.env.TELEROBOT_TOKEN || null;
  if (!tlsDir) {
    if (token) {
      console.error('TELEROBOT_TOKEN is ignored without TELEROBOT_TLS_DIR: a token is only '
        + 'sent over TLS');
    }
    return { credentials: grpc.credentials.createInsecure(), description: 'plaintext' };
  }
  const ca = readPem(tlsDir, 'ca.pem');
  if (token) {
    const bearer = grpc.credentials.createFromMetadataGenerator((_params, callback) => {
      const metadata = new grpc.Metadata();
      metadata.add('authorization', `Bearer ${token}`);
      callback(null, metadata);
    });
    return {
      credentials: grpc.credentials.combineChannelCredentials(grpc.credentials.createSsl(ca), bearer),
      description: 'TLS with a bearer token',
    };
  }
  const identity = args.identity || process.env.TELEROBOT_IDENTITY || DEFAULT_IDENTITY;
  const key = readPem(tlsDir, `${identity}.key`);
  const cert = readPem(tlsDir, `${identity}.pem`);
  return {
    credentials: grpc.credentials.createSsl(ca, key, cert),
    description: `mutual TLS as ${identity}`,
  };
}

function readPem(directory, name) {
  const file = path.join(directory, name);
  try {
    return fs.readFileSync(file);
  } catch (error) {
    throw new Error(`cannot read ${file}: ${error.code || error.message}; \`make certs\` writes `
      + 'the development certificates to var/pki');
  }
}

function load() {
  const definition = protoLoader.loadSync(
    ['telerobot/v1/proxy_robot.proto', HEALTH_PROTO],
    { ...LOADER_OPTIONS, includeDirs: [PROTO_ROOT] },
  );
  return grpc.loadPackageDefinition(definition);
}

// Calls a unary method and resolves to {ok, reply} or {ok: false, code, details}.
function call(client, method, request) {
  return new Promise((resolve) => {
    const deadline = new Date(Date.now() + DEADLINE_MS);
    client[method](request, { deadline }, (error, reply) => {
      if (error) {
        resolve({ ok: false, code: grpc.status[error.code], details: error.details });
      } else {
        resolve({ ok: true, reply });
      }
    });
  });
}

function fail(address, error) {
  console.log(JSON.stringify({ address, error }));
  process.exit(1);
}

async function main() {
  let args;
  try {
    args = parseArgs(process.argv.slice(2));
  } catch (error) {
    if (!(error instanceof UsageError)) throw error;
    console.error(`${error.message}\n${USAGE}`);
    process.exit(2);
  }
  const address = args.address || process.env.TELEROBOT_DECISION_SERVER_ADDRESS || DEFAULT_ADDRESS;
  let security;
  try {
    security = channelSecurity(args);
  } catch (error) {
    fail(address, error.message);
  }
  const pkg = load();
  const health = new pkg.grpc.health.v1.Health(address, security.credentials);
  const robot = new pkg.telerobot.v1.ProxyRobot(address, security.credentials);

  const result = { address, health: {} };
  for (const service of ['', 'telerobot.v1.ProxyRobot']) {
    const answer = await call(health, 'Check', { service });
    if (!answer.ok && answer.code === 'UNAVAILABLE') {
      // A refused TLS handshake (an unknown CA, a certificate the server will not take, or
      // plaintext against TLS) looks the same as an unreachable server: the channel never
      // gets ready.
      const hint = security.description === 'plaintext'
        ? ' (plaintext; if the station runs with TLS, set TELEROBOT_TLS_DIR)'
        : ` or the TLS handshake failed (${security.description})`;
      fail(address, `cannot reach ${address}${hint}: ${answer.details}`);
    }
    result.health[service || '(server)'] = answer.ok ? answer.reply.status : answer.code;
  }
  result.arm = await call(robot, 'GetArmInfo', {});  // which arm: its joints, limits, home
  result.status = await call(robot, 'GetStatus', {});
  result.state = await call(robot, 'GetState', {});
  console.log(JSON.stringify(result, null, 2));
  health.close();
  robot.close();
}

main().catch((error) => {
  console.error(error);
  process.exit(1);
});
