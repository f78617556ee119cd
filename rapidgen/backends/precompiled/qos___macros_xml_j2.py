# mypy: ignore-errors
# Template templates/qos/_macros.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "01d8c41ae010b66cf9b6d296847dc926e1ac0dfa0e4bead5f4df001505ce10f9"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_macros.xml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_locator = l_0_fastdds_endpoint = l_0_omg_endpoint = l_0_omg_partition = l_0_rti_participant = missing
    try:
        t_1 = environment.tests['none']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No test named 'none' found.")
    pass
    def macro(l_1_l):
        t_2 = []
        if l_1_l is missing:
            l_1_l = undefined("parameter 'l' was not provided", name='l')
        pass
        if environment.getattr(l_1_l, 'is_any'):
            pass
            t_2.append(
                '<locator/>',
            )
        else:
            pass
            t_2.extend((
                '<locator><',
                escape(environment.finalize(environment.getattr(l_1_l, 'kind'))),
                '><address>',
                escape(environment.finalize(environment.getattr(l_1_l, 'address'))),
                '</address>',
            ))
            if (not t_1(environment.getattr(l_1_l, 'physical_port'))):
                pass
                t_2.extend((
                    '<physical_port>',
                    escape(environment.finalize(environment.getattr(l_1_l, 'physical_port'))),
                    '</physical_port>',
                ))
            if (not t_1(environment.getattr(l_1_l, 'port'))):
                pass
                t_2.extend((
                    '<port>',
                    escape(environment.finalize(environment.getattr(l_1_l, 'port'))),
                    '</port>',
                ))
            t_2.extend((
                '</',
                escape(environment.finalize(environment.getattr(l_1_l, 'kind'))),
                '></locator>',
            ))
        return concat(t_2)
    context.exported_vars.add('locator')
    context.vars['locator'] = l_0_locator = Macro(environment, macro, 'locator', ('l',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_e, l_1_p):
        t_3 = []
        if l_1_e is missing:
            l_1_e = undefined("parameter 'e' was not provided", name='e')
        if l_1_p is missing:
            l_1_p = undefined("parameter 'p' was not provided", name='p')
        pass
        t_3.extend((
            '<topic>\n  <historyQos>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'history_kind'))),
            '</kind>\n',
        ))
        if environment.getattr(l_1_e, 'has_depth'):
            pass
            t_3.extend((
                '    <depth>',
                escape(environment.finalize(environment.getattr(l_1_e, 'history_depth'))),
                '</depth>\n',
            ))
        t_3.append(
            '  </historyQos>\n',
        )
        if environment.getattr(l_1_e, 'limits'):
            pass
            t_3.extend((
                '  <resourceLimitsQos>\n    <max_samples>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_samples'))),
                '</max_samples>\n    <max_instances>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_instances'))),
                '</max_instances>\n    <max_samples_per_instance>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_samples_per_instance'))),
                '</max_samples_per_instance>\n  </resourceLimitsQos>\n',
            ))
        t_3.extend((
            '</topic>\n<qos>\n  <reliability>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'reliability'))),
            '</kind>\n  </reliability>\n  <durability>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'durability'))),
            '</kind>\n  </durability>\n',
        ))
        if environment.getattr(l_1_e, 'publish_mode'):
            pass
            t_3.extend((
                '  <publishMode>\n    <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'publish_mode'))),
                '</kind>\n  </publishMode>\n',
            ))
        if environment.getattr(l_1_p, 'has_partition'):
            pass
            t_3.extend((
                '  <partition>\n    <names>\n      <name>',
                escape(environment.finalize(environment.getattr(l_1_p, 'partition'))),
                '</name>\n    </names>\n  </partition>\n',
            ))
        t_3.append(
            '</qos>',
        )
        return concat(t_3)
    context.exported_vars.add('fastdds_endpoint')
    context.vars['fastdds_endpoint'] = l_0_fastdds_endpoint = Macro(environment, macro, 'fastdds_endpoint', ('e', 'p'), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_e):
        t_4 = []
        if l_1_e is missing:
            l_1_e = undefined("parameter 'e' was not provided", name='e')
        pass
        if environment.getattr(l_1_e, 'reliability'):
            pass
            t_4.extend((
                '<reliability>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'reliability'))),
                '</kind>\n</reliability>\n',
            ))
        if environment.getattr(l_1_e, 'durability'):
            pass
            t_4.extend((
                '<durability>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'durability'))),
                '</kind>\n</durability>\n',
            ))
        if environment.getattr(l_1_e, 'has_history'):
            pass
            t_4.extend((
                '<history>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'history_kind'))),
                '</kind>\n',
            ))
            if environment.getattr(l_1_e, 'has_depth'):
                pass
                t_4.extend((
                    '  <depth>',
                    escape(environment.finalize(environment.getattr(l_1_e, 'history_depth'))),
                    '</depth>\n',
                ))
            t_4.append(
                '</history>\n',
            )
        if environment.getattr(l_1_e, 'publish_mode'):
            pass
            t_4.extend((
                '<publish_mode>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'publish_mode'))),
                '</kind>\n</publish_mode>\n',
            ))
        return concat(t_4)
    context.exported_vars.add('omg_endpoint')
    context.vars['omg_endpoint'] = l_0_omg_endpoint = Macro(environment, macro, 'omg_endpoint', ('e',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_name):
        t_5 = []
        if l_1_name is missing:
            l_1_name = undefined("parameter 'name' was not provided", name='name')
        pass
        t_5.extend((
            '<partition>\n  <name>\n    <element>',
            escape(environment.finalize(l_1_name)),
            '</element>\n  </name>\n</partition>',
        ))
        return concat(t_5)
    context.exported_vars.add('omg_partition')
    context.vars['omg_partition'] = l_0_omg_partition = Macro(environment, macro, 'omg_partition', ('name',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_p):
        t_6 = []
        if l_1_p is missing:
            l_1_p = undefined("parameter 'p' was not provided", name='p')
        pass
        if environment.getattr(l_1_p, 'has_mask'):
            pass
            t_6.extend((
                '<transport_builtin>\n  <mask>',
                escape(environment.finalize(environment.getattr(l_1_p, 'builtin_mask'))),
                '</mask>\n</transport_builtin>\n',
            ))
        if environment.getattr(l_1_p, 'sets_discovery'):
            pass
            t_6.append(
                '<discovery>\n  <initial_peers>\n',
            )
            for l_2_peer in environment.getattr(l_1_p, 'initial_peers'):
                _loop_vars = {}
                pass
                t_6.extend((
                    '    <element>',
                    escape(environment.finalize(l_2_peer)),
                    '</element>\n',
                ))
            l_2_peer = missing
            t_6.append(
                '  </initial_peers>\n',
            )
            if environment.getattr(l_1_p, 'has_multicast_receive'):
                pass
                t_6.append(
                    '  <multicast_receive_addresses>\n',
                )
                for l_2_a in environment.getattr(l_1_p, 'multicast_receive'):
                    _loop_vars = {}
                    pass
                    t_6.extend((
                        '    <element>',
                        escape(environment.finalize(l_2_a)),
                        '</element>\n',
                    ))
                l_2_a = missing
                t_6.append(
                    '  </multicast_receive_addresses>\n',
                )
            else:
                pass
                t_6.append(
                    '  <multicast_receive_addresses/>\n',
                )
            t_6.append(
                '</discovery>\n',
            )
        if environment.getattr(l_1_p, 'type_code_off'):
            pass
            t_6.append(
                '<resource_limits>\n  <type_code_max_serialized_length>0</type_code_max_serialized_length>\n  <type_object_max_serialized_length>0</type_object_max_serialized_length>\n</resource_limits>\n',
            )
        if environment.getattr(l_1_p, 'has_ports'):
            pass
            t_6.extend((
                '<wire_protocol>\n  <rtps_well_known_ports>\n    <port_base>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'base'))),
                '</port_base>\n    <domain_id_gain>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'domain_gain'))),
                '</domain_id_gain>\n    <participant_id_gain>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'participant_gain'))),
                '</participant_id_gain>\n    <builtin_multicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd0'))),
                '</builtin_multicast_port_offset>\n    <builtin_unicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd1'))),
                '</builtin_unicast_port_offset>\n    <user_multicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd2'))),
                '</user_multicast_port_offset>\n    <user_unicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd3'))),
                '</user_unicast_port_offset>\n  </rtps_well_known_ports>\n</wire_protocol>\n',
            ))
        if environment.getattr(l_1_p, 'has_properties'):
            pass
            t_6.append(
                '<property>\n  <value>\n',
            )
            for l_2_prop in environment.getattr(l_1_p, 'properties'):
                _loop_vars = {}
                pass
                t_6.extend((
                    '    <element>\n      <name>',
                    escape(environment.finalize(environment.getattr(l_2_prop, 'name'))),
                    '</name>\n      <value>',
                    escape(environment.finalize(environment.getattr(l_2_prop, 'value'))),
                    '</value>\n    </element>\n',
                ))
            l_2_prop = missing
            t_6.append(
                '  </value>\n</property>\n',
            )
        return concat(t_6)
    context.exported_vars.add('rti_participant')
    context.vars['rti_participant'] = l_0_rti_participant = Macro(environment, macro, 'rti_participant', ('p',), False, False, False, context.eval_ctx.autoescape)

blocks = {}
debug_info = '3=18&4=23&7=32&17=60&20=69&21=72&22=76&25=82&27=86&28=88&29=90&35=95&38=97&40=100&42=104&45=107&48=111&55=121&56=126&58=130&61=133&63=137&66=140&68=144&69=147&70=151&74=157&76=161&81=168&84=175&89=182&90=187&92=191&95=194&98=199&99=204&102=211&104=216&105=221&113=236&119=241&122=245&123=247&124=249&125=251&126=253&127=255&128=257&132=260&135=265&137=270&138=272'
