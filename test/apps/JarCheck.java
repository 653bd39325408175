// The Java side: decode every event of an LCM log with the classes of tdo-lcmtypes.jar (what
// lcm-spy does with the jar on its class path). Prints "decoded N, undecodable M, by type: ...".
//   java -cp lcm.jar:tdo-lcmtypes.jar JarCheck.java LOG
import java.io.EOFException;
import java.lang.reflect.InvocationTargetException;
import java.util.Map;
import java.util.TreeMap;
import lcm.logging.Log;

public class JarCheck {
  public static void main(String[] args) throws Exception {
    Map<String, Class<?>> types = Map.of(
        "TDO_MAP", tdo.map_t.class, "TDO_PLAN_REQUEST", tdo.plan_request_t.class,
        "TDO_TRAJECTORY", tdo.trajectory_t.class, "TDO_FEASIBILITY", tdo.feasibility_t.class,
        "TDO_STATUS", tdo.status_t.class, "TDO_OBSTACLES", tdo.obstacles_t.class,
        "TDO_UAV_STATE", tdo.vehicle_state_t.class, "TDO_SETPOINT", tdo.setpoint_t.class);
    Log log = new Log(args[0], "r");
    int decoded = 0, bad = 0;
    Map<String, Integer> byType = new TreeMap<>();
    while (true) {
      Log.Event ev;
      try {
        ev = log.readNext();
      } catch (EOFException e) {
        break;
      }
      Class<?> c = types.get(ev.channel);
      if (c == null) continue;
      try {
        c.getConstructor(byte[].class).newInstance((Object) ev.data);
        decoded++;
        byType.merge(c.getSimpleName(), 1, Integer::sum);
      } catch (InvocationTargetException e) {
        bad++;  // a malformed message recorded on purpose
      }
    }
    System.out.println("decoded " + decoded + ", undecodable " + bad + ", by type: " + byType);
  }
}
